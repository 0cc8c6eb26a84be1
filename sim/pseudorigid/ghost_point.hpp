// Reference points and ghost points (Ridgely 2001, §4.2.2, 4.3.3): massless points that
// move with a body. A ghost point also transfers a force applied to it onto the
// body's four masses so that the net force and the net moment about the CoM
// are preserved: the minimum-norm solution x = A^T (A A^T)^-1 b of the 6x12
// system [1 1 1 1; [r_1]x .. [r_4]x] x = [F; r_g x F]. The 12x3 map from F to
// the four mass forces is precomputed once in the body frame and rotated with
// the body's attitude at run time: F_i = R G_i R^T F.
//
// The point's position is the affine (barycentric) combination of the four
// mass positions that reproduces its body-frame location; it equals
// CoM + R r_g for an undeformed body and keeps position and velocity exactly
// consistent (v_g = sum w_i v_i) when the body flexes.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

namespace pronk::pseudorigid {

struct ReferencePoint {
  std::string name;
  int body = 0;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();  ///< body frame, relative to the CoM [m]
};

struct GhostPoint {
  std::string name;
  int body = 0;
  Eigen::Vector3d local = Eigen::Vector3d::Zero();    ///< body frame, relative to the CoM [m]
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();  ///< barycentric weights, sum 1
  std::array<Eigen::Matrix3d, 4> transfer;            ///< G_i (body frame)
};

/// Fills weights and transfer of `g` for a body with mass positions `local`.
void prepare_ghost_point(const std::array<Eigen::Vector3d, 4>& local, GhostPoint* g);

}  // namespace pronk::pseudorigid
