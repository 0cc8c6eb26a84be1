// One entry point for every fidelity: runs a robot scene in the model the scene
// names (impulse, pulse or the pseudo-rigid full model) and estimates the
// stability of its gait. The CLI, the evaluator, the map engine and the bench
// call these two functions; nothing else chooses a simulator by the model, so a
// new fidelity plugs in here.
#pragma once

#include <string>

#include "sim/robot/robot_simulator.hpp"
#include "sim/scene/scene.hpp"

namespace pronk {

struct RunOptions {
  bool record_trajectory = true;  ///< sample the trajectory every sample_interval
  bool record_strides = true;     ///< keep the per-stride records (the full model always does)
  /// Treat the initial state as a touchdown at t = 0 (reduced models only: the
  /// full model starts from a rigid initial state; std::invalid_argument there).
  bool start_at_touchdown = false;
};

/// The records every model writes (`run`), plus, for the full model, its samples,
/// per-stride actuator forces and slips, and accuracy monitors (empty otherwise).
struct RunResult : robot::RobotRunResult {
  scene::ModelKind model = scene::ModelKind::kImpulse;
  bool full_model() const { return scene::is_full_model(model); }
};

/// Simulates `scene` in scene.model. Numerical trouble ends the run with a status
/// and reason (never NaN); a full-model robot that cannot be built, or a run that would
/// hold more samples or strides than reduced/run_limits.hpp allows, throws
/// std::invalid_argument with the reason.
RunResult simulate(const scene::Scene& scene, const RunOptions& options = {});

/// Throws std::invalid_argument (with the reason) when scene.model cannot build
/// this robot (the full model's geometry checks); the reduced models build any scene.
void check_buildable(const scene::Scene& scene);

/// Stability of the gait (docs/studies.md): the spectral radius of the linearised
/// stride-to-stride map, and how it was obtained.
struct StabilityEstimate {
  bool ok = false;
  std::string reason;            ///< why no estimate, when !ok
  double spectral_radius = 0.0;  ///< the penalty when !ok
  /// "orbit_jacobian": the periodic orbit found and the stride map differentiated
  /// by finite differences (reduced models); "stride_map_fit": an affine map fitted
  /// to the touchdowns of a few disturbed runs (full model, as `pronk map` does).
  std::string method;
  long simulations = 0;       ///< stride-map evaluations or disturbed runs
  long strides = 0;           ///< simulated strides
  double fit_residual = 0.0;  ///< stride_map_fit: relative residual of the fit
};

/// The gait's stability in scene.model. Never throws for a gait that falls or
/// wanders: ok = false and spectral_radius = penalty.
StabilityEstimate analyze_stability(const scene::Scene& scene, double penalty = 10.0);

}  // namespace pronk
