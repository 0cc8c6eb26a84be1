// "method": "auto": the integration method and its step or tolerance for a mechanism (or the
// full-model robot's mechanism), chosen from the scene probe (scene_probe.hpp) and the user's
// accuracy target, before the run. Deterministic: the same scene gives the same choice.
//
// The rule (docs/solvers.md), in order, with a = accuracy (the largest sampled energy-balance
// drift allowed, relative to the run's energy scale) and omega = SceneProbe::omega_max:
//   1. no springs (omega = 0): nothing stiff, the step is accuracy-limited -> dopri5,
//      rtol = atol = a / 10 (order 5).
//   2. a < 1e-6: too tight for a second-order method -> radau5 (no contact) or rodas4
//      (contact: one linearisation per step copes with the switches), rtol = atol = a / 10.
//   3. dissipation that Verlet cannot take implicitly (min_norm ghost transfer with dampers
//      on ghost points) -> rodas4, rtol = atol = a / 10.
//   4. Verlet's step 0.8 x 2 / omega below 2e-5 s (more than 5e4 steps per simulated second;
//      the satellite's cost crossover, bench: k = 1e8 N/m) -> radau5, whose cost is flat in
//      the stiffness, rtol = atol = a / 100 (its estimate is looser per nominal tolerance);
//      a robot (restarts: its contacts switch at touchdown and lift-off, where RADAU5's
//      Newton iterations stall) -> rodas4 at the same tolerance (pr_running at 1e7 and
//      1e8 N/m: 0.40 and 0.34 s per simulated second).
//   5. an elastic contact is the stiffest mode (omega_c >= 0.9 omega): its ringing must be
//      resolved anyway, so the problem is not stiff (LSODA's test) -> dopri5,
//      rtol = atol = a x 1e-4 (its energy drift on elastic impacts is ~3e3 x its tolerance:
//      spring_leg_drop 2.9e-4 at 1e-7, 1.3e-3 at 1e-6).
//   6. otherwise -> verlet, h_fixed = the smaller of 0.8 x 2 / omega (0.7 x with restarts)
//      and, with an elastic
//      contact (SceneProbe::omega_elastic_contact), 0.7 / omega_c (its ringing resolved: the
//      elastic impacts' errors do not dissipate), rounded down to two digits, at most h_max;
//      energy_tol = a / 2 x min(1, 2 s / t_end): impacts and other large forces are
//      sub-stepped so that its bounded energy term stays within the budget, which shrinks
//      with the run's length because the offsets of the sub-step switches add up over the
//      impacts (docs/pseudorigid.md, "Energy budget"). For runs restarted at events (the
//      robot: touchdowns, apexes, foot switches) energy_tol = 0: there the restart offsets
//      of the sub-stepped scheme dominate (pr_running: 1.5e-3 with a budget of 5e-4,
//      6e-4 without at h = 1.2e-4 s).
//   7. no contact, a mechanism (checked after 5, before 4 and 6): smooth -> radau5 with
//      stage Jacobians, which steps over the stiff modes, rtol = atol = a / 10.
//   8. no contact, a robot (force legs; checked before 7): its pulses switch the hip forces,
//      so the steps are accuracy-limited -> dopri5 while its stability limit 3.3 / omega is
//      above 8e-5 s (the cost crossover on case 5: dopri5 at 1e8 N/m, radau5 at 1e9),
//      radau5 otherwise, rtol = atol = a / 1000 (the restarts: case 5 keeps 6e-4 at 1e-6,
//      5.8e-3 at 1e-5).
//   The order: 1, 2, 3, 5, 8, 7, 4, 6.
// cvode_bdf is never chosen: its BDF above order 2 is not A-stable and gains energy on the
// undamped vibrations of these models (docs/performance.md, quad hopper drop).
#pragma once

#include <string>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/scene_probe.hpp"

namespace pronk::pseudorigid {

/// What auto is asked for.
struct AutoRequest {
  /// Largest sampled energy-balance drift allowed, relative to the run's energy scale.
  double accuracy = 1e-3;
  double h_max = 0.1;     ///< the user's largest step [s]
  double t_end = 1.0;     ///< the run's length [s]
  bool restarts = false;  ///< the run restarts the integration at events (the robot)
  /// verlet: a mode [rad/s] that rings through the run and whose dynamics matter, so the
  /// step resolves it (omega h = 0.6) as well as staying stable; 0: none (quasi-static feet:
  /// the body on its landed feet, sim/robot/feet_step_bound.hpp).
  double resolve_omega = 0.0;
  /// verlet: the largest step of the run's flight segments [s] (MethodChoice::h_flight,
  /// at least the step); 0: none.
  double flight_step = 0.0;
};

/// What auto chose and why.
struct MethodChoice {
  ode::Method method = ode::Method::kVerlet;
  double h_fixed = 0.0;     ///< verlet: its step [s]
  double h_flight = 0.0;    ///< verlet: the step of flight segments [s], 0: h_fixed
  double energy_tol = 0.0;  ///< verlet: its energy budget, relative to the energy scale
  double rtol = 0.0;        ///< adaptive methods
  double atol = 0.0;        ///< adaptive methods
  double accuracy = 0.0;    ///< the request's
  SceneProbe probe;
  int rule = 0;        ///< which rule of the header chose (1..8)
  std::string reason;  ///< one line: "auto: verlet h=1.3e-4 s (stiffest mode ...)"
  /// > 0: this is the rerun's choice (refine_choice), after a first run that drifted by
  /// first_drift (relative) with the first choice's step or tolerance first_setting.
  int reruns = 0;
  double first_drift = 0.0;
};

/// Smallest accuracy the readers accept (and the largest: 0.5).
constexpr double kMinAccuracy = 1e-12;
constexpr double kMaxAccuracy = 0.5;
/// The solver settings auto chooses (the scene readers refuse them under "auto").
constexpr const char* kAutoChosenSettings[] = {"rtol", "atol", "h_fixed", "energy_tol", "h_flight"};

/// x rounded down to two significant digits (x > 0): auto's steps.
double round_down_2(double x);

/// Applies the rule of the header to a probe.
MethodChoice choose_method(const SceneProbe& probe, const AutoRequest& request);
/// Probes m and chooses.
MethodChoice choose_method(const Mechanism& m, const AutoRequest& request);

/// The check after the run: a completed run under auto whose sampled energy-balance drift
/// (relative) exceeds the accuracy is rerun once with refine_choice's setting. The probe
/// cannot foresee every impact (a 10 m/s drop: Verlet at energy_tol 5e-4 drifted 4.8e-3).
bool needs_rerun(const MethodChoice& c, double drift_relative);
/// The rerun's choice: the same method with its knob scaled so that the drift, assumed
/// proportional to energy_tol or to the tolerance (to h^2 for Verlet without a budget), aims
/// at half the accuracy; at most a factor 1000 at once. The reason gains "; rerun: ...".
MethodChoice refine_choice(const MethodChoice& c, double drift_relative);

/// Writes the choice into solver options (method, h_fixed or rtol/atol; the rest, h_max,
/// max_steps, ..., stay the user's) and verlet's relative energy budget into *energy_tol.
void apply_choice(const MethodChoice& c, ode::SolverOptions* solver, double* energy_tol);

}  // namespace pronk::pseudorigid
