// The robot in the full model: the hybrid loop that integrates the pseudo-rigid
// robot (pseudo_rigid_robot.hpp) with events for touchdown (the CoM falls
// through the leg length, as in the reduced models), apex and falls, runs the
// same three-layer controller as the reduced models at every touchdown (body
// controller -> impulse allocation -> leg controllers), drives the leg
// actuators for the stance, places the legs at the apex when the hips rotate,
// and restarts the solver (keeping its step) after every switch.
//
// Leg layer for spring legs (Ridgely 2001, §2.8.1): the leg springs return the touchdown
// momentum (an elastic rebound reverses v_z), so the actuators deliver the
// request minus that rebound, m (sqrt(2 g h) - |v_z|) vertically: negative
// (downward) forces lower the hop, positive ones raise it (Ridgely 2001, fig. 2.13).
#pragma once

#include <string>
#include <vector>

#include "sim/pseudorigid/energy.hpp"
#include "sim/pseudorigid/method_choice.hpp"
#include "sim/pseudorigid/stiffness.hpp"
#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::robot {

/// Samples of the full model on the output grid (beside RunResult::trajectory).
struct RobotSample {
  double t = 0.0;                      ///< [s]
  pseudorigid::Energies energies;      ///< stored energies by class [J]
  double dissipated = 0.0;             ///< dampers and friction up to t [J]
  double actuator_work = 0.0;          ///< leg actuators and hip placement up to t [J]
  std::vector<double> actuator_force;  ///< per leg, signed (+ pushes the body up) [N]
  std::vector<double> normal_force;    ///< per foot, ground normal force [N]
  std::vector<double> foot_z;          ///< per foot height [m]
};

/// Accuracy monitors and outputs only the full model has.
struct RobotMonitors {
  double energy_scale = 0.0;        ///< reference energy: M g (initial CoM height + hop height) [J]
  double energy_drift = 0.0;        ///< max |balance(t) - balance(0)| [J]
  double max_strain = 0.0;          ///< largest internal strain [-]
  double max_penetration = 0.0;     ///< deepest ground penetration or slide violation [m]
  double max_slip = 0.0;            ///< largest horizontal foot travel within one stance [m]
  double max_friction_ratio = 0.0;  ///< largest |F_t| / N seen (mu = sliding) [-]
  double hip_work = 0.0;            ///< energy put in by placing the legs [J]
  double positive_hip_work = 0.0;   ///< its positive part, placement by placement [J]
  double actuator_work = 0.0;       ///< net work of leg actuators and hip placement [J]
  double positive_actuator_work = 0.0;  ///< the same counting only positive power [J]
  /// Energy in the legs (leg springs + feet's kinetic energy relative to the
  /// body) at the flight apexes: the foot vibration on the leg springs [J].
  double max_leg_vibration_energy = 0.0;
  long zero_length_triggers = 0;
  pseudorigid::StiffnessChoice stiffness;                    ///< what "auto" chose
  double internal_stiffness = 0.0, contact_stiffness = 0.0;  ///< used [N/m]
  /// false for MuJoCo runs: its contact and joint dampers dissipate by its own laws, so the
  /// pseudo-rigid energy balance is not an accuracy monitor there (energy_drift is 0).
  bool energy_measured = true;
  bool method_auto = false;                 ///< the scene's solver was "auto"
  pseudorigid::MethodChoice method_choice;  ///< what it chose (when method_auto)

  /// energy_drift relative to energy_scale (0 when the scale is 0).
  double drift_relative() const { return energy_scale > 0.0 ? energy_drift / energy_scale : 0.0; }
};

struct RobotRunResult {
  reduced::RunResult run;  ///< the same records as the reduced models
  std::vector<RobotSample> samples;
  /// Per stride: signed actuator force of each leg during its stance [N].
  std::vector<std::vector<double>> stride_actuator_force;
  /// Per stride: largest horizontal foot travel during the stance [m].
  std::vector<double> stride_slip;
  /// Per stride (free stance hips): the stance's measured contact time, first foot down to
  /// the last foot up, as the next placement plans with it [s].
  std::vector<double> stride_contact;
  RobotMonitors monitors;
  /// "model": "mujoco": the robot's MJCF model, its keyframe "initial" the run's start (the
  /// outputs write it as robot.xml); empty for the other models.
  std::string mjcf;
  /// "model": "mujoco": CPU time of MuJoCo's mj_step alone (the run's cost.wall_time adds the
  /// controller, events and records) [s]; 0 otherwise.
  double engine_cpu = 0.0;
};

struct RobotRunOptions {
  bool record_trajectory = true;
};

/// Simulates scene s with the full model's robot: in MuJoCo when s.model is kMujoco (throws
/// std::invalid_argument when this build has no MuJoCo), else in the pseudo-rigid model.
/// Throws std::invalid_argument for a robot that cannot be built (reason given) or a run
/// that would hold more records than reduced/run_limits.hpp allows (the numbers given);
/// numerical trouble ends the run with a status and reason, never NaN; a fixed step too
/// long to see every flight ends it `diverged` at t = 0.
RobotRunResult simulate(const scene::Scene& s, const RobotRunOptions& options = {});

}  // namespace pronk::robot
