// The robot of a scene as a pseudo-rigid mechanism (Ridgely 2001, §2.7-2.8; docs/full_model.md):
// the body as four masses held by six stiff springs, hips as ghost points or
// dummy masses (Ridgely 2001, §4.3), gravity on every mass (uniform field: the same net
// force and moment as gravity at the CoM), and per leg either nothing but a
// force at the hip (`force` legs, Ridgely 2001, §2.7) or a foot mass on a line through
// the hip (prismatic leg) with a leg spring and damper, on the ground plane
// z = 0 with regularised Coulomb friction on the feet (`spring` legs, Ridgely 2001, §2.8).
// The leg actuators and hip placement are run-time inputs of RobotSystem
// (robot_system.hpp).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/pseudorigid/model.hpp"
#include "sim/pseudorigid/stiffness.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::robot {

struct RobotModel {
  pseudorigid::Mechanism mechanism;  ///< const for runs: they change its MechanismInputs
  int body = 0;                      ///< index of the robot body
  /// Per leg (every hip of the scene, disabled ones included):
  std::vector<pseudorigid::NodeRef> hip_node;  ///< where leg forces act (ghost or dummy mass)
  std::vector<Eigen::Vector3d> hip;            ///< hip position, body frame [m]
  std::vector<int> foot;                       ///< foot mass index; -1 for force legs
  std::vector<int> slide;                      ///< line-surface index of the leg; -1 without
  std::vector<double> rest_length;             ///< leg spring rest length [m]
  std::vector<int> leg_spring;                 ///< leg spring connection index; -1 without
  /// Leg direction hip -> foot, body frame (unit); initially straight down.
  std::vector<Eigen::Vector3d> direction;
  int ground = -1;  ///< ground plane surface index; -1 without feet
  bool spring_legs = false;
  /// Spring legs with quasi-static (massless) feet: no foot masses, slides, leg springs or
  /// ground in the mechanism; RobotSystem holds the feet (robot_system_feet.cpp). foot, slide
  /// and leg_spring are -1, rest_length holds the legs' nominal rest lengths.
  bool quasi_static_feet = false;
  double body_mass = 0.0;                  ///< scene body mass (dummies included) [kg]
  pseudorigid::StiffnessChoice stiffness;  ///< what "auto" chose (if asked)
};

/// Builds the mechanism of scene s. Throws std::invalid_argument with a reason
/// (e.g. a leg too short for its hip, dummy masses heavier than the body, no gravity).
RobotModel build_robot(const scene::Scene& s);

}  // namespace pronk::robot
