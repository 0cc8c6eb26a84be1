// Point masses (Ridgely 2001, §4.2.1): six states each, position and momentum.
#pragma once

#include <string>

#include <Eigen/Dense>

namespace pronk::pseudorigid {

/// A point mass. Body masses are regular masses created by the body
/// construction; a dummy mass (Ridgely 2001, §4.3.2) is a light mass (dummy_ratio of its
/// body's mass) tied to the body's masses by stiff internal connections.
struct Mass {
  std::string name;
  double mass = 1.0;                                   ///< [kg]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< initial position, world [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< initial velocity, world [m/s]
  int body = -1;      ///< body whose main mass this is, -1 for a free mass
  int dummy_of = -1;  ///< body a dummy mass belongs to, -1 otherwise
};

/// A grounded point (attached to nothing, no states; Ridgely 2001, §4.2.4).
struct Anchor {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< world [m]
};

}  // namespace pronk::pseudorigid
