// Bodies of four equal point masses (Ridgely 2001, §4.2.4) and their construction from
// a mass, a centre of mass and an inertia tensor.
//
// Construction: the second-moment tensor P = sum m_i r_i r_i^T of point masses
// relates to the inertia tensor by I = tr(P) 1 - P, so P = tr(I)/2 1 - I. In the
// principal frame P = diag(Py, ...) with Pxx = (Iyy + Izz - Ixx)/2 >= 0 exactly
// when the triangle inequalities hold. Four masses m/4 at the alternating
// corners (a,b,c), (a,-b,-c), (-a,b,-c), (-a,-b,c) of a box have zero first
// moment, zero products and sum m_i x_i^2 = m a^2, so a = sqrt(Pxx/m) etc. A
// full tensor is diagonalised (eigenvectors as a proper rotation V) and the
// masses placed at V r_i.
#pragma once

#include <array>
#include <string>

#include <Eigen/Dense>

namespace pronk::pseudorigid {

/// Mass properties a body is built from.
struct BodySpec {
  std::string name = "body";
  double mass = 1.0;                                       ///< [kg]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();   ///< about the CoM, body frame [kg m^2]
  Eigen::Vector3d com = Eigen::Vector3d::Zero();           ///< initial CoM, world [m]
  Eigen::Matrix3d attitude = Eigen::Matrix3d::Identity();  ///< initial body-to-world rotation
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      ///< initial CoM velocity, world [m/s]
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();  ///< initial angular velocity, world [rad/s]
  double internal_stiffness = 1e6;                  ///< internal springs [N/m]
  double internal_damping = 0.0;                    ///< internal dampers [N s/m]
  /// One rigid body (Newton-Euler, unit quaternion) instead of four masses and six springs:
  /// the same mass and inertia tensor, no internal springs (rigid_body.hpp).
  bool rigid = false;
};

/// A body as the model holds it.
struct Body {
  std::string name;
  int first_mass = 0;  ///< its four main masses are first_mass .. first_mass+3
  double mass = 1.0;   ///< [kg]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();  ///< requested tensor, body frame [kg m^2]
  std::array<Eigen::Vector3d, 4> local;  ///< mass positions relative to the CoM, body frame [m]
  Eigen::Matrix3d geometric_inverse;     ///< (sum |r|^2 1 - r r^T)^-1 of `local` [1/m^2]
  double size = 1.0;                     ///< largest |local| [m]
  double min_edge = 1.0;                 ///< shortest internal spring [m]
  /// Rigid body (BodySpec::rigid): first_mass is ONE mass (the whole body at its CoM, its
  /// translation), and the body owns 7 more states after all masses' (rigid_body.hpp): the
  /// attitude quaternion (w, x, y, z) and the world angular momentum [N m s]. `local` is
  /// still the four-mass placement (size, min_edge and "auto" stiffness use it).
  bool rigid = false;
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Identity();  ///< body frame [1/(kg m^2)]
  Eigen::Quaterniond attitude0 = Eigen::Quaterniond::Identity();  ///< rigid: initial attitude
  Eigen::Vector3d angular_momentum0 = Eigen::Vector3d::Zero();    ///< rigid: initial, world
  Eigen::Vector3d principal_moments = Eigen::Vector3d::Ones();    ///< rigid [kg m^2]
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity();   ///< rigid: columns, body frame
};

/// Places four masses for the tensor. Returns false with a reason (naming the
/// violated inequality) for non-symmetric, non-positive or triangle-violating
/// tensors and for flat (degenerate) bodies that six springs cannot hold rigid.
bool construct_body(double mass, const Eigen::Matrix3d& inertia,
                    std::array<Eigen::Vector3d, 4>* local, std::string* error);

/// The inertia tensor of four point masses (each mass/4) about their centroid.
Eigen::Matrix3d point_mass_inertia(double mass, const std::array<Eigen::Vector3d, 4>& local);

}  // namespace pronk::pseudorigid
