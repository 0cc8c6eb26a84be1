// The hybrid run loop every model shares (the reduced models, pseudo-rigid mechanisms, the
// robot in the full model): integrate to the next event or scheduled time, hand the event to
// the model, restart the solver at the (possibly changed) state keeping its step, until the
// model ends the run. The model supplies its ODE system, its event functions, what happens
// at an event or a scheduled time (controller, switch, impulse), its step observer (samples,
// flows, monitors) and what a failed integration means; the loop owns the cycle (Drake's
// Simulator over a System with witness functions; MuJoCo's one mj_step).
#pragma once

#include <span>
#include <string>

#include "sim/ode/solver.hpp"

namespace pronk::run {

/// What the loop does after a segment the model handled.
enum class Next { kContinue, kStop };

/// How a segment ended.
struct Segment {
  double t = 0.0;                   ///< time reached [s] (an event's time)
  ode::IntegrateResult integrated;  ///< reason kReachedEnd also when nothing was integrated
  /// The model's pending event (HybridModel::take_pending_event) is due: nothing was
  /// integrated.
  bool pending = false;
  /// The event index into the events() of the segment, -1 without an event.
  int event() const {
    return integrated.reason == ode::StopReason::kEvent ? integrated.event_index : -1;
  }
};

/// One model's side of the loop. The model keeps its own result record; the loop keeps t,
/// the state and the stepper.
class HybridModel {
 public:
  virtual ~HybridModel() = default;
  /// The system the solver integrates.
  virtual const ode::OdeSystem& system() const = 0;
  /// The options integrate() checks: event tolerance, step budget, crawl guard.
  virtual const ode::SolverOptions& integration_options() const = 0;
  /// The run starts at (t0, y), the stepper already reset there (initial samples).
  virtual void start(const ode::Stepper& stepper, const ode::Vec& y) = 0;
  /// True once when an event is due at the current state before any integration (a run
  /// that starts at a touchdown); the model handles it in on_segment_end.
  virtual bool take_pending_event() { return false; }
  /// End of the next segment: the run's end or the next scheduled switch [s].
  virtual double segment_end(double t) const = 0;
  /// The event functions armed for the next segment (the current mode's).
  virtual std::span<const ode::EventFunction* const> events() const = 0;
  /// Observer of the accepted steps (samples, flows, monitors), or null.
  virtual ode::StepObserver* observer() = 0;
  /// The integration failed (step-size collapse, non-finite state, step budget, crawl, or
  /// the observer stopped it) at (t, y): the model records why; the run ends.
  virtual void on_failure(const Segment& segment, const ode::Vec& y,
                          const ode::Stepper& stepper) = 0;
  /// The segment ended at (segment.t, y): the model checks the state (falls, divergence),
  /// handles the event or the scheduled time and may change y. kStop ends the run.
  virtual Next on_segment_end(const Segment& segment, ode::Vec& y, const ode::Stepper& stepper) = 0;
  /// The solver restarts at the segment's end (after kContinue).
  virtual void on_restart() {}
  /// Method verlet: the grid step [s] of the segment that starts at (t, y), set before each
  /// (re)start (ode::set_verlet_step); 0 keeps the stepper's.
  virtual double fixed_step(double /*t*/, const ode::Vec& /*y*/) const { return 0.0; }
};

/// Where the run ended.
struct HybridEnd {
  double t = 0.0;  ///< [s]
  ode::Vec y;      ///< the state at t, as the model left it
};

/// Runs `model` from (t0, y0) with `stepper` until the model stops it or an integration
/// fails; the stepper keeps its adapted step across the restarts at events.
HybridEnd run_hybrid(HybridModel& model, ode::Stepper& stepper, double t0, const ode::Vec& y0);

/// True for the integration outcomes that end a run (not an event, not the segment's end).
bool is_failure(ode::StopReason reason);

/// The event-driven models' reason for a failed integration: "step-size collapse at t = T s",
/// "non-finite state at t = T s" (each followed by `note`), or the solver options' step-budget
/// and crawl reasons.
std::string failure_reason(const Segment& segment, const ode::Stepper& stepper,
                           const ode::SolverOptions& options, const std::string& note = "");

/// x with 6 significant digits, as the run reasons print times and sizes.
std::string fmt(double x);

}  // namespace pronk::run
