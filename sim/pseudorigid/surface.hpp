// Constraint surfaces (Ridgely 2001, §4.2.5). Each constrained node is held by a stiff
// zero-rest-length spring (plus optional damper) to its projection on the
// surface:
//   plane  one-sided contact: F = -k (n.r) n - b (n.v) n while n.r < 0
//          (bilateral: on both sides, a slot holding the node in the plane)
//   line   a prismatic joint:  F = -k (1 - d d^T) r - b (1 - d d^T) v
//   point  a pivot:            F = -k r - b v
// with r = x_node - x_surface, v the relative velocity. A grounded plane may add
// regularised Coulomb friction (Ridgely 2001, §2.8 feet; MuJoCo-like ground contact):
//   F_t = -mu N v_t / sqrt(|v_t|^2 + v_s^2),  N = max(0, -k (n.r) - b (n.v)),
// v_t = v - (n.v) n: Coulomb's law above the slip velocity v_s, viscous below it
// (a stuck foot creeps at |v_t| ~ v_s |F_t| / (mu N)). A surface is grounded
// (its point and direction fixed in the world; no states) or attached to a body
// (its point is one of the body's ghost points, its direction turns with the
// body, and the reaction acts on the body through that ghost point).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/pseudorigid/node.hpp"

namespace pronk::pseudorigid {

enum class SurfaceType { kPlane, kLine, kPoint };

/// The components of u a surface of this type with unit direction d constrains, P u: (d.u) d
/// (plane), u - (d.u) d (line), u (point); P is never formed.
inline Eigen::Vector3d project_onto(SurfaceType type, const Eigen::Vector3d& d,
                                    const Eigen::Vector3d& u) {
  switch (type) {
    case SurfaceType::kPlane:
      return d.dot(u) * d;
    case SurfaceType::kLine:
      return u - d.dot(u) * d;
    case SurfaceType::kPoint:
      break;
  }
  return u;
}

/// How far a node at r from the surface violates it [m]: |d.r| for a plane, |P r| otherwise.
inline double penetration_of(SurfaceType type, const Eigen::Vector3d& d, const Eigen::Vector3d& r) {
  return type == SurfaceType::kPlane ? std::abs(d.dot(r)) : project_onto(type, d, r).norm();
}

/// P as a matrix (the Jacobian's blocks).
inline Eigen::Matrix3d projector(SurfaceType type, const Eigen::Vector3d& d) {
  switch (type) {
    case SurfaceType::kPlane:
      return d * d.transpose();
    case SurfaceType::kLine:
      return Eigen::Matrix3d::Identity() - d * d.transpose();
    case SurfaceType::kPoint:
      break;
  }
  return Eigen::Matrix3d::Identity();
}

struct Surface {
  std::string name;
  SurfaceType type = SurfaceType::kPlane;
  int body = -1;   ///< attached body, -1 when grounded
  int ghost = -1;  ///< attached: ghost point that carries the surface's point
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       ///< grounded: a point on it, world [m]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit normal (plane) or direction
                                                         ///< (line); body frame when attached
  std::vector<NodeRef> nodes;                            ///< constrained nodes
  double stiffness = 1e5;                                ///< [N/m]
  double damping = 0.0;                                  ///< [N s/m]
  double friction = 0.0;        ///< Coulomb coefficient mu (grounded planes only) [-]
  double slip_velocity = 1e-3;  ///< regularisation velocity v_s of the friction law [m/s]
  bool bilateral = false;       ///< plane: holds on both sides (no contact, no friction)
};

}  // namespace pronk::pseudorigid
