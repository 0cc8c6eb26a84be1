// The measurements of `pronk bench` (docs/performance.md): work-precision sweeps of every
// solver on the reference scenes, the pseudo-rigid stiffness sweep, the fidelity ladder and its
// robustness, and the quad hopper drop that MuJoCo is compared with. Each group runs in its own
// file of app/bench/ and returns plain records; app/bench/report.cpp writes them (JSON, CSV),
// app/bench/figures.cpp draws them, and bench_command.cpp merges the peers' results.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/measure.hpp"
#include "optimize/progress.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::app::bench {

/// How much to measure.
struct BenchConfig {
  bool quick = false;       ///< CI size: fewer points, shorter runs (< 1 min in total)
  int repeat = 3;           ///< timed repeats per point; the median wall time is reported
  std::string studies_dir;  ///< the shipped studies/ directory (scenes are read from it)
  /// Progress within a stage where its count is known (the robustness rungs' cells).
  optimize::ProgressStyle progress = optimize::ProgressStyle::kOff;
};

/// One point of a work-precision diagram.
struct WorkPoint {
  std::string problem;     ///< "satellite", "satellite_stiffness", "hopper", "hopper_stride_map"
  std::string solver;      ///< euler, rk2, rk4, dopri5, rodas4, radau5, cvode_bdf, verlet
  std::string variant;     ///< error norm of the pseudo-rigid runs ("state", "body"; cvode_bdf:
                           ///< its linear solver, "klu"), else ""
  double stiffness = 0.0;  ///< internal stiffness of the pseudo-rigid body [N/m]; 0: n/a
  double tol = 0.0;        ///< rtol = atol of adaptive methods; 0 for fixed step
  double h = 0.0;          ///< fixed step [s]; 0 for adaptive methods
  double t_end = 0.0;      ///< simulated time [s]
  std::string status;      ///< completed, diverged, fell, ...
  Cost cost;               ///< median times; the solver's counters (stride map: steps = map
                           ///< evaluations)
  /// Errors by name (only those that apply, only for completed runs):
  ///   omega_final   |w(t_end) - w_exact(t_end)| / |w0|, satellite vs the analytic precession
  ///   omega_l2      RMS over the output grid of |w - w_ref| / |w0| vs the tight reference run
  ///   omega_final_ref  |w(t_end) - w_ref(t_end)| / |w0| vs the tight reference run of the same
  ///                 stiffness: the solver's error without the model's (stiffness sweep)
  ///   model_omega_error  stiffness sweep: omega_final of that reference (the model's error)
  ///   final_state   satellite: RMS of y(t_end) - y_ref(t_end) over all states [m, N s];
  ///                 hopper: |CoM position(t_end) - reference| [m]
  ///   l2_series     hopper: RMS over the 5 ms output grid of |CoM - CoM_ref| [m]
  ///   touchdown_time  hopper: max |t_td,k - t_td,k,ref| over the strides [s]
  ///   fixed_point   stride map: |s* - s*_ref|_inf of the periodic orbit [m, m/s, rad, rad/s]
  std::map<std::string, double> errors;
};

/// Fitted convergence order (slope of log error vs log step) of a fixed-step method.
struct OrderFit {
  std::string problem, solver, error;
  double order = 0.0;
  int points = 0;
};

/// One model rung of the fidelity ladder at one duty-cycle setting.
struct FidelityPoint {
  std::string model;            ///< impulse, pulse, rigid, pseudo_rigid (four-mass body)
  bool available = true;        ///< false: the rung exists but cannot run yet (see note)
  std::string note;             ///< why unavailable, or remarks
  double pulse_duration = 0.0;  ///< stance pulse T [s] (pulse model); 0 for impulse
  std::string status;
  double t_end = 0.0;           ///< simulated time [s]
  double wall_s = 0.0;          ///< median [s]
  double cpu_s = 0.0;           ///< median CPU time [s]
  double cost_per_sim_s = 0.0;  ///< CPU time per simulated second [s/s]
  std::string ran_model;        ///< the model simulate() ran (RunResult::model)
  long rhs_evaluations = 0;     ///< the solver's right-hand sides (the timed run)
  long jacobians = 0;           ///< the solver's Jacobians (the timed run; 0: explicit)
  long strides = 0;
  double mean_duty = 0.0;            ///< stance / stride time
  double mean_apex = 0.0;            ///< mean apex height over strides 2.. [m]
  double apex_rms_vs_impulse = 0.0;  ///< RMS of apex_k - apex_k(impulse) over strides 2.. [m]
  /// Of the stride map at its fixed point: impulse and pulse by finite differences of the map
  /// (reduced::analyze_stability); pseudo_rigid, which has no map to evaluate, the fit below.
  double spectral_radius = 0.0;
  std::string spectral_radius_method;  ///< "stride_map" or "fit"
  /// Estimate from the affine map fitted to the touchdowns of 4 small-perturbation runs of
  /// 6 s (reduced::estimate_stride_map), for every rung: on impulse and pulse it checks the
  /// estimator against the stride map; 10 when no estimate.
  double spectral_radius_fit = 0.0;
  bool fit_ok = false;
  double fit_residual_rel = 0.0;  ///< RMS fit residual / RMS of the next states [-]
  bool stable = false;  ///< spectral radius < 1 with an orbit found (pseudo_rigid: and no fall)
  double fixed_point_vs_impulse = 0.0;  ///< |s* - s*_impulse|_inf
  /// rigid rung: max |apex_k - apex_k(pseudo_rigid)| over the strides both have, at the same
  /// pulse [m] (its agreement with the four-mass body); -1 elsewhere.
  double apex_max_vs_four_mass = -1.0;
  std::vector<double> apexes;  ///< apex heights of strides 2.. [m] (not written out)
};

/// One rung at one duty cycle: a cell of the ladder's robustness map (the seeded
/// disturbance trials and the "stabilized" criterion of `pronk map`).
struct RobustnessCell {
  double duty = 0.0;  ///< duty-axis value (sets the stance pulse T) [-]
  long trials = 0, stabilized = 0, fell = 0;
  double fraction = 0.0;   ///< stabilized / trials [-]
  double mean_duty = 0.0;  ///< measured, mean over the trials [-]
  /// Undisturbed gait at this duty: stride map (impulse, pulse) or its fit (pseudo_rigid);
  /// 10 when there is no periodic orbit / no estimate.
  double spectral_radius = 0.0;
  long only_this = 0;          ///< trials this rung stabilizes and the pulse rung does not
  long only_pulse = 0;         ///< trials the pulse rung stabilizes and this rung does not
  std::vector<bool> verdicts;  ///< stabilized, per trial (not written out)
};

/// One rung's robustness over the duty cycles.
struct RungRobustness {
  std::string model;
  bool available = true;
  std::string note;
  std::vector<RobustnessCell> cells;
  /// The map's boundary: the largest duty at which every trial stabilizes, bisected between
  /// the last good and the next cell (3 probes: to 0.0125).
  /// "bisected", "all_good" (boundary >= the last duty) or "none_good" (< the first duty).
  std::string boundary_status;
  double boundary = 0.0;            ///< [-]
  double bad = 0.0;                 ///< the bracket's bad end (bisected; else = boundary) [-]
  double first_good = 0.0;          ///< lowest duty with every trial stabilized [-]
  long probes = 0;                  ///< bisection probes (each runs the trials)
  long disagreements_vs_pulse = 0;  ///< over all cells: only_this + only_pulse
  double cpu_s = 0.0;               ///< CPU time of this rung's trials, probes and radii [s]
};

/// Robustness of every rung at a few duty cycles: row 0 (no extra roll) of the shipped
/// map_seed_duty study — its scene, seed, disturbances, trial duration and criterion —
/// at fewer duties and trials, every rung on the same trials.
struct LadderRobustness {
  std::string study;  ///< the map study the trials come from
  long trials = 0;    ///< per cell and rung
  std::uint64_t seed = 0;
  double trial_duration = 0.0;  ///< [s]
  double resolution = 0.0;      ///< of the boundary bisection [-]
  std::vector<double> duties;
  std::vector<RungRobustness> rungs;
};

/// A rung of the ladder: runs the robot scene (its pulse settings chosen by the caller) in
/// one model.
struct FidelityRung {
  std::string model;
  std::function<FidelityPoint(const scene::Scene&, const BenchConfig&)> run;
};
std::vector<FidelityRung> fidelity_rungs();
/// The full model's settings of the ladder's rigid and pseudo_rigid rungs (the scene's
/// "pseudo_rigid" object): force legs, internal springs of 1e6 N/m.
constexpr const char* kFullModelSettings = R"({"legs": "force", "internal_stiffness": 1e6})";

/// Pseudo-rigid satellite (the torque-free precessing satellite of
/// tests/pseudorigid/scenes.hpp), k = 1e6 N/m, 20 s: every solver and tolerance.
std::vector<WorkPoint> satellite_work_precision(const BenchConfig& c);
/// The same satellite for k = 1e4 .. 1e8 N/m with RODAS4 (state and body norm) and DOPRI5.
std::vector<WorkPoint> satellite_stiffness_sweep(const BenchConfig& c);
/// The reduced legged pulse hopper (studies/scenes/case3_legged_pulse.json), `duration` [s]
/// simulated: the scene of the hopper's work-precision and of the fidelity ladder.
scene::Scene hopper_scene(const BenchConfig& c, double duration);
/// Reduced legged pulse hopper: every solver, step and tolerance; and the stride-map fixed
/// point per tolerance.
std::vector<WorkPoint> hopper_work_precision(const BenchConfig& c);
/// Fits the orders of the fixed-step methods on `points` (final-state error vs h).
std::vector<OrderFit> fit_orders(const std::vector<WorkPoint>& points);
/// The fidelity ladder on the legged hopper for a few pulse durations.
std::vector<FidelityPoint> fidelity_ladder(const BenchConfig& c);
/// Robustness of the ladder's rungs at duty 0.1, 0.2, 0.3, 0.4 (8 trials of 12 s per cell;
/// the pseudo_rigid rung, about 2 min of CPU, is not run with --quick).
LadderRobustness ladder_robustness(const BenchConfig& c);
/// The quad spring hopper drop in the pseudo-rigid model (the scene the MuJoCo peer
/// mirrors): per tolerance cost, energy-balance drift (energy_error_rel: max drift / drop
/// energy m g 0.15 m), apex heights. JSON records.
nlohmann::json quad_hopper_drop(const BenchConfig& c);
/// The quad hopper drop as a mechanism document (docs/pseudorigid.md), `t_end` simulated [s].
nlohmann::json quad_hopper_mechanism(double t_end);

}  // namespace pronk::app::bench
