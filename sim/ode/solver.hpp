// ODE solvers behind one interface: options, counters, the stepper and the
// event-aware integration driver.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "sim/ode/error_norm.hpp"
#include "sim/ode/ode_system.hpp"

namespace pronk::ode {

class VerletInfo;

/// The integration methods pronk offers.
enum class Method {
  kEuler,     ///< explicit Euler, fixed step, order 1
  kRk2,       ///< explicit midpoint (RK2), fixed step, order 2
  kRk4,       ///< classic Runge-Kutta, fixed step, order 4
  kDopri5,    ///< Dormand-Prince 5(4), adaptive, 4th-order dense output
  kRodas4,    ///< Rosenbrock RODAS4 (Hairer-Wanner), L-stable, adaptive, 3rd-order dense output
  kRadau5,    ///< Radau IIA order 5 (Hairer-Wanner RADAU5), fully implicit (Newton), L-stable,
              ///< adaptive, collocation dense output; for stiff rotating springs
  kCvodeBdf,  ///< SUNDIALS CVODE, variable-order BDF (1-5), adaptive, Nordsieck dense output;
              ///< the system's analytic Jacobian with KLU or dense LU (sim/ode/cvode.cpp)
  kVerlet,    ///< velocity Verlet (Stormer-Verlet, kick-drift-kick), fixed step, order 2,
              ///< symplectic: one RHS per step, no energy drift on conservative mechanisms;
              ///< only for MechanicalSystems (sim/ode/mechanical_system.hpp)
};

/// "euler", "rk2", "rk4", "dopri5", "rodas4", "radau5", "cvode_bdf", "verlet".
std::string_view to_string(Method m);
/// Parses the names of to_string; returns false on an unknown name.
bool parse_method(std::string_view name, Method* out);
/// True for methods with error control (step size adapted).
bool is_adaptive(Method m);

/// cvode_bdf: the linear solver of CVODE's Newton iteration.
enum class CvodeLinearSolver {
  kAuto,   ///< KLU (sparse) when the system has an analytic Jacobian, dense LU otherwise
  kDense,  ///< SUNDIALS' dense LU (with difference quotients without an analytic Jacobian)
  kKlu,    ///< KLU on the analytic Jacobian's pattern (dense LU without an analytic Jacobian)
};

/// "auto", "dense", "klu".
std::string_view to_string(CvodeLinearSolver s);
/// Parses the names of to_string; returns false on an unknown name.
bool parse_cvode_linear_solver(std::string_view name, CvodeLinearSolver* out);

/// Where integrate() restarts after an event located inside a step (method verlet).
enum class EventRestart {
  kInterpolant,  ///< at the step's dense output (cubic Hermite) at the event time
  kStep,         ///< at the end of the step retaken from its start to the event time
                 ///< (Stepper::retake): a state the method itself reaches, so the energy
                 ///< balance's error converges with the step; other methods use kInterpolant
};

/// "interpolant", "step".
std::string_view to_string(EventRestart r);
/// Parses the names of to_string; returns false on an unknown name.
bool parse_event_restart(std::string_view name, EventRestart* out);

/// How to integrate. Defaults suit the reduced models.
struct SolverOptions {
  Method method = Method::kDopri5;
  double rtol = 1e-9;     ///< relative tolerance (adaptive methods)
  double atol = 1e-9;     ///< absolute tolerance (adaptive methods)
  double h_fixed = 1e-3;  ///< step [s] of the fixed-step methods
  /// verlet: the step [s] of the segments a run's model calls flight (its stiff modes all
  /// off: massless feet in the air leave the body on gravity alone; run::HybridModel::
  /// fixed_step), h_fixed in the others; 0 (default) takes h_fixed throughout. Method
  /// "auto" sets it for quasi-static feet.
  double h_flight = 0.0;
  /// verlet only: 0 (default) takes every step at h_fixed. A positive budget [J] makes
  /// h_fixed the step of the output grid, each taken as 2^j equal sub-steps so that Verlet's
  /// bounded energy term T_net (VerletInfo::verlet_term) stays within the budget; beyond
  /// 4096 sub-steps or below h_min it is not kept. Needs MechanicalSystem::kinetic_energy().
  /// docs/pseudorigid.md, "Energy budget".
  double verlet_energy_budget = 0.0;
  double h_initial = 0.0;    ///< first trial step [s] of adaptive methods; 0 = automatic
  double h_max = 0.1;        ///< largest step [s]
  double h_min = 1e-13;      ///< adaptive step below this is a step-size collapse [s]
  double event_tol = 1e-13;  ///< event time tolerance [s]
  /// verlet: the state a run restarts from after an event inside a step (docs/pseudorigid.md,
  /// "Restarts at events"); the other methods always restart from their dense output.
  EventRestart event_restart = EventRestart::kInterpolant;
  /// Step attempts (accepted + rejected) of the whole run before it ends with a reason: the
  /// stepper's counters, which carry over reset() (restarts at events), not one integrate() call.
  long max_steps = 100000000;
  /// Adaptive methods: the crawl guard. A run whose step attempts exceed
  /// kStepBudgetFloor + max_steps_per_second x (simulated time since it started) ends with a
  /// reason instead of grinding on at tiny steps (docs/pseudorigid.md, "Crawl guard"). 0 turns
  /// the guard off. [1/s]
  double max_steps_per_second = 1e6;
  /// rodas4, radau5: systems with at most this many states factorise with dense LU,
  /// larger ones with Eigen's SparseLU (the crossover: bench_lu_crossover, docs/pseudorigid.md).
  int dense_lu_max_dimension = 150;
  /// radau5 on mechanical systems with an analytic Jacobian: when the Newton iteration with
  /// one Jacobian shared by the stages fails, switch to one Jacobian per stage (at the stages'
  /// starting values) for a span of steps (docs/pseudorigid.md, "Solver: RADAU5"). Stiff
  /// springs that rotate need it; false keeps Hairer's iteration. Systems above
  /// dense_lu_max_dimension keep it too (the stage system is factorised dense).
  bool radau5_stage_jacobians = true;
  /// cvode_bdf: KLU or dense LU for CVODE's Newton matrix I - gamma J (docs/pseudorigid.md).
  CvodeLinearSolver cvode_linear_solver = CvodeLinearSolver::kAuto;

  /// Checks every field; on failure writes "field: value: rule" into *error.
  bool validate(std::string* error) const;

  /// Step attempts every run may take before the crawl guard applies.
  static constexpr long kStepBudgetFloor = 100000;
  /// True when `attempts` step attempts over `simulated` seconds [s] exceed the crawl
  /// guard's budget (adaptive methods with max_steps_per_second > 0 only).
  bool crawling(long attempts, double simulated) const;
  /// "N step attempts for T s simulated up to t = ... s (budget ...)": the reason of a crawl.
  std::string crawl_reason(long attempts, double simulated, double t) const;
  /// "step budget exceeded: N step attempts ... max_steps ... at t = ...": the reason of a run
  /// that used up max_steps.
  std::string step_limit_reason(long attempts, double t) const;
};

/// Cost counters of a run; accumulated over restarts.
struct SolverCounters {
  long steps_accepted = 0;
  long steps_rejected = 0;
  long rhs_evaluations = 0;
  long events = 0;
  long jacobian_evaluations = 0;  ///< analytic or finite-difference Jacobians (rodas4, radau5)
  long lu_factorizations = 0;     ///< LU factorisations of I/(gamma h) - J (rodas4; radau5
                                  ///< counts its real + complex pair as one)

  /// Adds another run's counters (auto's rerun reports both runs' cost).
  SolverCounters& operator+=(const SolverCounters& o) {
    steps_accepted += o.steps_accepted;
    steps_rejected += o.steps_rejected;
    rhs_evaluations += o.rhs_evaluations;
    events += o.events;
    jacobian_evaluations += o.jacobian_evaluations;
    lu_factorizations += o.lu_factorizations;
    return *this;
  }
};

/// Outcome of one step attempt.
enum class StepStatus { kOk, kStepSizeCollapse, kNonFinite };

/// A one-step solver with dense output over its last accepted step.
/// Usage: reset(t0, y0) -> repeatedly step() -> dense() inside [t_prev(), t()].
/// reset() may be called many times (at every touchdown/liftoff): adaptive
/// solvers keep their adapted step size across resets.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Restarts at (t, y), e.g. after an impulse changed y. Keeps the adapted step.
  virtual void reset(const OdeSystem& sys, double t, const Vec& y) = 0;
  /// Advances one accepted step, never beyond t_limit (> t()). Rejected
  /// attempts are retried internally and counted.
  virtual StepStatus step(const OdeSystem& sys, double t_limit) = 0;
  /// Interpolates y at t in [t_prev(), t()] with the method's dense output.
  virtual void dense(double t, Vec& y_out) const = 0;
  virtual double t() const = 0;
  virtual double t_prev() const = 0;
  virtual const Vec& y() const = 0;
  /// Step size the next step() will try [s].
  virtual double h() const = 0;
  virtual const SolverCounters& counters() const = 0;
  /// Mutable counters (integrate() counts located events here).
  virtual SolverCounters& mutable_counters() = 0;
  /// Method verlet's energy bookkeeping (sim/ode/verlet.hpp); null for the other methods.
  virtual const VerletInfo* verlet_info() const { return nullptr; }
  /// True when retake() can replace the last step (method verlet).
  virtual bool can_retake() const { return false; }
  /// Replaces the last accepted step by one from its start to t, t_prev() < t <= the step's
  /// end as step() took it (a retaken step can be retaken again), so that t() == t and y() is
  /// the method's own state there (EventRestart::kStep). Returns false, changing nothing, for
  /// a method that cannot (then restart from dense()), a t outside the step, or a retaken step
  /// that is not finite.
  virtual bool retake(const OdeSystem& /*sys*/, double /*t*/) { return false; }
  /// An engine that steps on its own (MuJoCo): what it is and why a step failed, for the run's
  /// reason ("MuJoCo Euler, step 0.001 s; warning ..."); empty for pronk's own methods.
  virtual std::string failure_note() const { return {}; }
};

/// Creates the stepper of options.method for systems of dimension n. `norm`: the error norm
/// of the adaptive methods (dopri5, rodas4, radau5) for the stepper's life; cvode_bdf keeps
/// CVODE's weighted RMS norm but takes a scaled norm's per-state atol (a custom norm, such as
/// the body norm, it cannot use: it keeps the plain one); the fixed-step methods ignore it.
std::unique_ptr<Stepper> make_stepper(const SolverOptions& options, int n, ErrorNorm norm = {});

/// Why integrate() returned.
/// kMaxSteps: the stepper's counters (accepted + rejected, since it was made) reached
/// SolverOptions::max_steps. kCrawling: SolverOptions::crawling() (the crawl guard).
/// kStopped: the observer asked to stop (StepObserver::stop_requested) after a step.
enum class StopReason {
  kReachedEnd,
  kEvent,
  kStepSizeCollapse,
  kNonFinite,
  kMaxSteps,
  kCrawling,
  kStopped
};

struct IntegrateResult {
  StopReason reason = StopReason::kReachedEnd;
  int event_index = -1;  ///< index into events when reason == kEvent
  double t = 0.0;        ///< time reached (event time when reason == kEvent)
  double t_start = 0.0;  ///< time the call started from [s]
  long attempts = 0;     ///< step attempts (accepted + rejected) of this call
};

/// Integrates from the stepper's current (t, y) until t_end or until the first
/// event fires (earliest in time, located on the dense output by a bracketing
/// root finder to options.event_tol). On an event the stepper is reset to the
/// event point (t_event, y(t_event)) so the caller can modify the state and
/// reset again: y(t_event) from the dense output, or (options.event_restart kStep, on a
/// stepper that can) from the step retaken to t_event. `on_step` (optional) is called after every
/// accepted step with the stepper, e.g. to sample output on a fixed grid via dense().
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// Called after each accepted step; dense() is valid on [t_prev(), t_stop].
  virtual void on_step(const Stepper& stepper, double t_stop) = 0;
  /// Checked after each on_step: true ends integrate() with StopReason::kStopped at the
  /// step's end (e.g. a monitor that found the run diverging).
  virtual bool stop_requested() const { return false; }
};

IntegrateResult integrate(const OdeSystem& sys, Stepper& stepper, double t_end,
                          std::span<const EventFunction* const> events,
                          const SolverOptions& options, StepObserver* observer = nullptr);

}  // namespace pronk::ode
