// The event-aware integration driver.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sim/ode/solver.hpp"

namespace pronk::ode {
namespace {

/// Crossing sign of an event over a step: -1 falling, +1 rising, 0 none.
/// Falling: g_prev > 0 and g_new <= 0; rising: g_prev < 0 and g_new >= 0.
int crossing(int direction, double g_prev, double g_new) {
  if (direction <= 0 && g_prev > 0.0 && g_new <= 0.0) return -1;
  if (direction >= 0 && g_prev < 0.0 && g_new >= 0.0) return +1;
  return 0;
}

/// Locates the crossing of an event inside [a, b] with the Illinois method (safeguarded by
/// bisection when progress stalls); g_at(t) is the event's value at t. g_a is strictly on the
/// pre-crossing side, g_b on the post side (sign `dir`); `first`, when inside, is the first
/// trial. Returns the post-side end of a final bracket no wider than tol [s].
template <class G>
double locate(const G& g_at, int dir, double a, double g_a, double b, double g_b, double tol,
              double first = std::numeric_limits<double>::quiet_NaN()) {
  auto is_post = [dir](double g) { return dir < 0 ? g <= 0.0 : g >= 0.0; };
  int last_side = 0;  // +1: b moved last, -1: a moved last
  bool bisect_next = false;
  for (int iter = 0; iter < 400 && b - a > tol; ++iter) {
    const double width = b - a;
    double t = 0.5 * (a + b);
    if (iter == 0 && first > a && first < b) {
      t = first;
    } else if (!bisect_next) {
      const double ts = b - g_b * (b - a) / (g_b - g_a);
      // Keep the trial strictly inside so the bracket always shrinks.
      const double margin = 0.25 * tol;
      if (std::isfinite(ts)) t = std::clamp(ts, a + margin, b - margin);
    }
    // Past t ~ 256 s the margin is below the spacing of doubles, so a secant trial can round
    // onto an end of a still wide bracket: bisect then, and stop only when not even the
    // midpoint lies strictly inside (the bracket is one double wide).
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    if (!(t > a && t < b)) break;  // no representable point inside the bracket
    const double g = g_at(t);
    if (is_post(g)) {
      b = t;
      g_b = g;
      if (last_side == +1) g_a *= 0.5;  // Illinois: damp the stale end
      last_side = +1;
    } else {
      a = t;
      g_a = g;
      if (last_side == -1) g_b *= 0.5;
      last_side = -1;
    }
    bisect_next = (b - a) > 0.5 * width;
  }
  return b;
}

/// EventRestart::kStep: the crossing of `event` (located at t_dense on the dense output) on
/// the stepper's own trajectory, every trial a retake of the step to it, and the stepper left
/// retaken to it. Returns NaN, with the step as it was, when a retake fails.
double locate_retaken(const OdeSystem& sys, const EventFunction& event, Stepper& stepper, int dir,
                      double a, double g_a, double b, double g_b, double tol, double t_dense) {
  bool failed = false;
  auto g_at = [&](double t) {
    if (failed || !stepper.retake(sys, t)) {
      failed = true;
      return std::numeric_limits<double>::quiet_NaN();
    }
    return event.value(t, stepper.y());
  };
  const double t = locate(g_at, dir, a, g_a, b, g_b, tol, t_dense);
  if (failed || !stepper.retake(sys, t)) {
    stepper.retake(sys, b);  // the whole step again, bit for bit
    return std::numeric_limits<double>::quiet_NaN();
  }
  return t;
}

}  // namespace

IntegrateResult integrate(const OdeSystem& sys, Stepper& stepper, double t_end,
                          std::span<const EventFunction* const> events,
                          const SolverOptions& options, StepObserver* observer) {
  IntegrateResult result;
  result.t = stepper.t();
  result.t_start = stepper.t();
  const std::size_t ne = events.size();
  std::vector<double> g_prev(ne), g_new(ne);
  Vec y_event(sys.dimension());
  for (std::size_t i = 0; i < ne; ++i) g_prev[i] = events[i]->value(stepper.t(), stepper.y());

  const SolverCounters& c = stepper.counters();
  const long attempts_at_start = c.steps_accepted + c.steps_rejected;
  while (stepper.t() < t_end) {
    const long attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
    if (c.steps_accepted + c.steps_rejected >= options.max_steps) {  // the whole run's budget
      result.reason = StopReason::kMaxSteps;
      result.t = stepper.t();
      result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
      return result;
    }
    if (options.crawling(attempts, stepper.t() - result.t_start)) {
      result.reason = StopReason::kCrawling;
      result.t = stepper.t();
      result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
      return result;
    }
    const StepStatus status = stepper.step(sys, t_end);
    if (status != StepStatus::kOk) {
      result.reason =
          status == StepStatus::kNonFinite ? StopReason::kNonFinite : StopReason::kStepSizeCollapse;
      result.t = stepper.t();
      result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
      return result;
    }
    const double t0 = stepper.t_prev();
    const double t1 = stepper.t();
    int fired = -1, fired_dir = 0;
    double t_fire = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ne; ++i) {
      g_new[i] = events[i]->value(t1, stepper.y());
      if (!std::isfinite(g_new[i])) {  // never let a NaN event pass silently
        result.reason = StopReason::kNonFinite;
        result.event_index = static_cast<int>(i);
        result.t = t1;
        result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
        return result;
      }
      const int dir = crossing(events[i]->direction(), g_prev[i], g_new[i]);
      if (dir == 0) continue;
      const EventFunction& event = *events[i];
      auto g_dense = [&](double t) {
        stepper.dense(t, y_event);
        return event.value(t, y_event);
      };
      const double te = locate(g_dense, dir, t0, g_prev[i], t1, g_new[i], options.event_tol);
      if (te < t_fire) {
        t_fire = te;
        fired = static_cast<int>(i);
        fired_dir = dir;
      }
    }
    if (fired >= 0) {
      // The restart point: the step retaken to the event (its own state; the observer then
      // books the cut step whole), or the dense output there.
      bool retaken = false;
      if (options.event_restart == EventRestart::kStep && stepper.can_retake()) {
        const double te = locate_retaken(sys, *events[fired], stepper, fired_dir, t0, g_prev[fired],
                                         t1, g_new[fired], options.event_tol, t_fire);
        retaken = !std::isnan(te);
        if (retaken) t_fire = te;
      }
      if (observer != nullptr) observer->on_step(stepper, t_fire);
      if (retaken) {
        y_event = stepper.y();
      } else {
        stepper.dense(t_fire, y_event);
      }
      stepper.reset(sys, t_fire, y_event);
      ++stepper.mutable_counters().events;
      result.reason = observer != nullptr && observer->stop_requested() ? StopReason::kStopped
                                                                        : StopReason::kEvent;
      result.event_index = fired;
      result.t = t_fire;
      result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
      return result;
    }
    if (observer != nullptr) {
      observer->on_step(stepper, t1);
      if (observer->stop_requested()) {
        result.reason = StopReason::kStopped;
        result.t = t1;
        result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
        return result;
      }
    }
    g_prev.swap(g_new);
  }
  result.reason = StopReason::kReachedEnd;
  result.t = stepper.t();
  result.attempts = c.steps_accepted + c.steps_rejected - attempts_at_start;
  return result;
}

}  // namespace pronk::ode
