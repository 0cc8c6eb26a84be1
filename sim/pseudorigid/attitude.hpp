// Attitude and angular velocity of a body from its four masses (Ridgely 2001, §3.4.4,
// 3.4.6), and the derivative of that attitude with respect to the mass
// positions (for the analytic Jacobian).
#pragma once

#include <array>

#include <Eigen/Dense>

namespace pronk::pseudorigid {

/// Kinematics of one body at one state.
struct BodyFrame {
  Eigen::Vector3d com = Eigen::Vector3d::Zero();           ///< centroid of the masses [m]
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();  ///< [m/s]
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< body-to-world, proper rotation
  Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();   ///< S = R^T M (symmetric) [m^2]
};

/// Orthogonal Procrustes (Kabsch): the proper rotation R minimising
/// sum |R local_i - (x_i - c)|^2: the rotation factor of the polar
/// decomposition of M = sum (x_i - c) local_i^T (Newton iteration), or, when M
/// is singular or reflecting, from its SVD with the reflection mapped to the
/// nearest proper rotation.
/// `start`: a rotation near the answer (the frame of a nearby state) to begin
/// the iteration from; without it the start is taken from M itself.
BodyFrame fit_attitude(const std::array<Eigen::Vector3d, 4>& x,
                       const std::array<Eigen::Vector3d, 4>& local,
                       const Eigen::Matrix3d* start = nullptr);

/// Least-squares angular velocity (world frame) [rad/s] from mass positions and
/// velocities: argmin sum |v_i - v_c - w x (x_i - c)|^2.
Eigen::Vector3d fit_angular_velocity(const std::array<Eigen::Vector3d, 4>& x,
                                     const std::array<Eigen::Vector3d, 4>& v);

/// d(omega_body)/d(x_k) for the Kabsch rotation: dR = R [omega_body]x, and
/// omega_body = sum_k Omega_k dx_k with Omega_k = (tr S 1 - S)^-1 [local_k]x R^T.
std::array<Eigen::Matrix3d, 4> attitude_derivative(const BodyFrame& frame,
                                                   const std::array<Eigen::Vector3d, 4>& local);

/// Cross-product matrix [v]x.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

}  // namespace pronk::pseudorigid
