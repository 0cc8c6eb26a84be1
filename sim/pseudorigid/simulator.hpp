// Runs a mechanism: integration with the chosen solver, sampling on a fixed
// output grid via dense output, energy accounting, accuracy monitors and
// divergence detection (non-finite state, energy blow-up, step-size
// collapse). Divergence ends the run with a status and a reason; every number
// in the result is finite.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/energy.hpp"
#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

enum class RunStatus { kCompleted, kDiverged };
std::string_view to_string(RunStatus s);

struct RunSummary {
  RunStatus status = RunStatus::kCompleted;
  std::string reason = "reached t_end";
  // Trajectory samples on the output grid (t = 0, dt, ..., last time reached).
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y;
  std::vector<Energies> energies;
  std::vector<double> dissipated;     ///< energy dissipated up to t [J]
  std::vector<double> actuator_work;  ///< work done by actuators and body forces up to t [J]
  // Cost.
  ode::SolverCounters counters;
  double wall_time = 0.0;  ///< [s]
  // Accuracy monitors.
  double energy_scale = 0.0;              ///< reference energy of the scene [J]
  double energy_drift = 0.0;              ///< max |balance(t) - balance(0)| [J]
  double max_strain = 0.0;                ///< largest internal strain seen
  double max_penetration = 0.0;           ///< deepest penetration / constraint violation [m]
  long zero_length_triggers = 0;          ///< RHS evaluations in which the zero-length rule fired
  std::vector<double> max_surface_force;  ///< per surface [N]
  double jacobian_check_error = -1.0;     ///< relative, when requested; -1 = not run
  double t_reached = 0.0;                 ///< [s]
  /// Non-fatal diagnostics, each listed once: id -> one-line explanation with the numbers.
  ///   energy_balance_drift      a completed run whose energy balance drifted by more than
  ///                             1e-2 of the energy scale (blow-up is energy_blowup_factor)
  ///   strain_above_budget       max internal strain > simulation.strain_budget (bodies flex:
  ///                             the internal springs are too soft for the load)
  ///   penetration_above_budget  max penetration / constraint violation > penetration_budget
  ///   zero_length_rule          a connection of (near) zero length had no direction; the
  ///                             terms that need one were dropped in N RHS evaluations
  ///   near_degenerate_inertia   a slender body (Imin/Imax < 1e-2) whose axial spin rate the
  ///                             internal strain perturbs by > 1e-3 (estimate: strain x
  ///                             Imax/Imin; momentum and energy stay accurate)
  std::map<std::string, std::string> warnings;

  /// energy_drift relative to energy_scale (0 when the scene has no energy scale).
  double drift_relative() const { return energy_scale > 0.0 ? energy_drift / energy_scale : 0.0; }
};

/// Simulates m from t = 0 to m.simulation.t_end.
RunSummary simulate(const Mechanism& m);

}  // namespace pronk::pseudorigid
