// What one simulation run produced: status and reason, per-stride records, the
// sampled trajectory, cost counters and accuracy monitors (Ceres' Summary).
// Shared by every model so their outputs can be compared line by line.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/control/allocation.hpp"
#include "sim/ode/solver.hpp"

namespace pronk::reduced {

enum class RunStatus {
  kCompleted,  ///< ran for the requested duration / number of strides
  kFell,       ///< CoM too low or body tilted past the fall limit
  kDiverged,   ///< non-finite state or step-size collapse
};
std::string_view to_string(RunStatus s);

/// One stride: from touchdown k to touchdown k+1.
struct StrideRecord {
  long index = 0;
  double t_touchdown = 0.0;                               ///< [s]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     ///< CoM at touchdown [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();     ///< CoM velocity at touchdown [m/s]
  Eigen::Vector3d euler123 = Eigen::Vector3d::Zero();     ///< attitude at touchdown, 1-2-3 [rad]
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();        ///< body rates at touchdown [rad/s]
  Eigen::Vector3d setpoint = Eigen::Vector3d::Zero();     ///< x_d(t_touchdown) [m]
  Eigen::Vector3d P_requested = Eigen::Vector3d::Zero();  ///< body controller, world [N s]
  Eigen::Vector3d H_requested = Eigen::Vector3d::Zero();  ///< body controller, body [N m s]
  Eigen::Vector3d P_delivered =
      Eigen::Vector3d::Zero();  ///< legs (incl. gravity comp.), world [N s]
  Eigen::Vector3d H_delivered = Eigen::Vector3d::Zero();  ///< legs, body [N m s]
  double gravity_compensation = 0.0;                      ///< [N s]
  double stance_duration = 0.0;                           ///< [s]
  double stride_time = 0.0;                               ///< to the next touchdown [s]; 0 if none
  double duty_cycle = 0.0;  ///< stance / stride time; 0 if no next touchdown
  bool has_apex = false;
  double apex_height = 0.0;     ///< CoM height at the flight apex of this stride [m]
  double peak_leg_force = 0.0;  ///< largest |F_i| in the stance [N]
  int active_legs = 0;
  control::AllocationStatus allocation = control::AllocationStatus::kOk;
};

/// Trajectory sample on the output grid.
struct Sample {
  double t = 0.0;                                       ///< [s]
  Eigen::Vector3d position, velocity, euler123, omega;  ///< [m], [m/s], [rad], [rad/s]
  Eigen::Vector3d setpoint;                             ///< [m]
  bool stance = false;
  Eigen::Vector3d leg_force_world = Eigen::Vector3d::Zero();  ///< Σ leg forces [N]
};

/// Accuracy monitors.
struct Monitors {
  double max_event_residual = 0.0;         ///< max |z - l| at located touchdowns [m]
  double max_flight_energy_drift = 0.0;    ///< max |ΔE| over a flight / (m g h) [-]
  double max_quaternion_norm_error = 0.0;  ///< max | |q| - 1 | before renormalising [-]
};

struct RunCost {
  ode::SolverCounters solver;
  long touchdowns = 0;
  double wall_time = 0.0;  ///< [s]
};

struct RunResult {
  RunStatus status = RunStatus::kCompleted;
  std::string reason;
  double t_end = 0.0;  ///< simulated time reached [s]
  std::vector<StrideRecord> strides;
  std::vector<Sample> trajectory;
  RunCost cost;
  Monitors monitors;
  std::map<std::string, long> warnings;  ///< counted non-fatal problems
  /// Final body state.
  Eigen::Vector3d final_position = Eigen::Vector3d::Zero(),
                  final_velocity = Eigen::Vector3d::Zero(),
                  final_euler123 = Eigen::Vector3d::Zero(), final_omega = Eigen::Vector3d::Zero();
  Eigen::Quaterniond final_attitude = Eigen::Quaterniond::Identity();  ///< body -> world
};

}  // namespace pronk::reduced
