// The measured state of the body that controllers see (assumed perfectly
// measured, Ridgely 2001, §2.4.1). Every model, reduced or pseudo-rigid, produces it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pronk::control {

struct BodyState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();            ///< CoM, world [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();            ///< CoM velocity, world [m/s]
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  ///< body -> world
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();        ///< body -> world
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();  ///< angular velocity, body frame [rad/s]
  /// 1-2-3 Euler angles [rad]: exact conversion of the attitude, or the
  /// integrated states of the seed's small-angle formulation.
  Eigen::Vector3d euler123 = Eigen::Vector3d::Zero();
};

}  // namespace pronk::control
