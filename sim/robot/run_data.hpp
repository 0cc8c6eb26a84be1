// What a robot run changes as it goes (the mechanism's run-time inputs, the actuators'
// commands, the controller's adapted terms), beside the const RobotModel.
#pragma once

#include <cmath>
#include <vector>

#include "sim/pseudorigid/inputs.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Vector3d;

/// What a robot run changes as it goes, beside the const RobotModel (MuJoCo's mjData beside
/// its mjModel): the mechanism's run-time inputs, whose leg rest lengths and slide surfaces
/// the hip placement and the foot switches set (RobotSystem reads them there), the leg
/// actuators' commands, and the controller's adapted terms.
struct RunData {
  RunData(const RobotModel& model, const scene::Scene& scene)
      : inputs(model.mechanism),
        push(model.hip.size(), Vector3d::UnitZ()),
        leg_force(model.hip.size(), 0.0),
        off_time(model.hip.size(), 0.0),
        stride_force(model.hip.size(), 0.0),
        armed_force(model.hip.size(), 0.0),
        armed_duration(model.hip.size(), 0.0) {
    for (size_t i = 0; i < model.hip.size(); ++i) push[i] = -model.direction[i];
    // Expected stance duration of spring legs [s]: half a period of the body on its leg
    // springs until a stance is measured (free stance hips measure every stance).
    spring_stance =
        model.spring_legs
            ? M_PI * std::sqrt(scene.body.mass / (scene.pseudo_rigid.leg_stiffness *
                                                  static_cast<double>(model.hip.size())))
            : 0.0;
  }
  pr::MechanismInputs inputs;        ///< hip placement and the feet turn the slides
  std::vector<Vector3d> push;        ///< body-frame push direction of each actuator
  std::vector<double> leg_force;     ///< actuator force of each leg now [N]
  std::vector<double> off_time;      ///< when each actuator switches off [s]
  std::vector<double> stride_force;  ///< the stance's actuator forces, for the stride record [N]
  /// Spring legs: the actuators fire in the thrust phase, from the bottom of the stance (CoM
  /// velocity rising through zero) on, so a downward force lowers the takeoff speed and an
  /// upward one raises it (Ridgely 2001, fig. 2.13).
  bool armed = false;
  std::vector<double> armed_force, armed_duration;
  Vector3d common_push = Vector3d::UnitZ();  ///< legs' push direction, body frame
  double spring_stance = 0.0;                ///< expected stance duration of spring legs [s]
  double hop_trim = 0.0;   ///< hop-height feedback: extra takeoff speed asked [m/s]
  double apex_trim = 0.0;  ///< hop-height feedback of the energy thrust: extra apex asked [m]
  Vector3d position_trim = Vector3d::Zero();  ///< integral action: position offset seen [m]
  Eigen::Vector2d attitude_trim = Eigen::Vector2d::Zero();  ///< integral action: roll, pitch [rad]
  /// Leg placement's integral action: horizontal impulse added to the placement's request
  /// (world x, y) [N s]; placed: the horizontal request the legs were placed for, this
  /// stride (valid when has_placed) [N s].
  Eigen::Vector2d placement_trim = Eigen::Vector2d::Zero();
  Eigen::Vector2d placed = Eigen::Vector2d::Zero();
  bool has_placed = false;
  double placed_response = 1.0;  ///< the placement's 1 - c (free_leg_response) [-]
};

}  // namespace pronk::robot::detail
