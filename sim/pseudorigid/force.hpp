// Applied forces and actuators (Ridgely 2001, §3.2, 4.3): world-relative forces (fixed
// direction in the world, e.g. a thrust or gravity at the CoM), body-relative
// forces (the direction turns with the body, e.g. a leg force at a hip), and
// the seed's impulse actuator (a force of given magnitude along a body-fixed
// direction until its time integral reaches the requested impulse). Gravity on
// every mass is Mechanism::gravity. The controller-driven force actuator is a
// Connection of kind kActuator (a clamped PD length controller, connection.hpp).
#pragma once

#include <limits>
#include <string>

#include <Eigen/Core>

#include "sim/pseudorigid/node.hpp"

namespace pronk::pseudorigid {

struct WorldForce {
  std::string name;
  NodeRef node;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< world frame [N]
};

struct BodyForce {
  std::string name;
  NodeRef node;
  int body = 0;                                            ///< whose attitude turns the force
  Eigen::Vector3d force = Eigen::Vector3d::Zero();         ///< body frame [N]
  double t_start = 0.0;                                    ///< on from [s]
  double t_end = std::numeric_limits<double>::infinity();  ///< off from [s]
};

struct ImpulseActuator {
  std::string name;
  NodeRef node;
  int body = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit, body frame
  double force = 1.0;                                    ///< magnitude while on [N]
  double impulse = 0.0;                                  ///< requested impulse [N s]
  double t_start = 0.0;                                  ///< [s]
  double duration() const { return impulse / force; }    ///< [s]
};

}  // namespace pronk::pseudorigid
