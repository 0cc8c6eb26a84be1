#include "sim/run/hybrid_run.hpp"

#include <sstream>

#include "sim/ode/verlet.hpp"

namespace pronk::run {

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

bool is_failure(ode::StopReason reason) {
  return reason != ode::StopReason::kReachedEnd && reason != ode::StopReason::kEvent;
}

std::string failure_reason(const Segment& segment, const ode::Stepper& stepper,
                           const ode::SolverOptions& options, const std::string& note) {
  const double t = segment.t;
  const ode::IntegrateResult& r = segment.integrated;
  switch (r.reason) {
    case ode::StopReason::kStepSizeCollapse:
      return "step-size collapse at t = " + fmt(t) + " s" + note;
    case ode::StopReason::kNonFinite:
      return "non-finite state at t = " + fmt(t) + " s" + note;
    case ode::StopReason::kMaxSteps:
      return options.step_limit_reason(
          stepper.counters().steps_accepted + stepper.counters().steps_rejected, t);
    case ode::StopReason::kCrawling:
      return options.crawl_reason(r.attempts, t - r.t_start, t);
    default:
      return "stopped at t = " + fmt(t) + " s";
  }
}

namespace {

/// (Re)starts the stepper at (t, y) on the step the model asks for there.
void restart(HybridModel& model, ode::Stepper& stepper, double t, const ode::Vec& y) {
  const double h = model.fixed_step(t, y);
  if (h > 0.0) ode::set_verlet_step(stepper, h);
  stepper.reset(model.system(), t, y);
}

}  // namespace

HybridEnd run_hybrid(HybridModel& model, ode::Stepper& stepper, double t0, const ode::Vec& y0) {
  HybridEnd end{t0, y0};
  restart(model, stepper, t0, y0);
  model.start(stepper, end.y);
  for (;;) {
    Segment seg;
    seg.pending = model.take_pending_event();
    const double t_target = model.segment_end(end.t);
    seg.integrated.t = end.t;
    if (!seg.pending && t_target > end.t) {
      seg.integrated = ode::integrate(model.system(), stepper, t_target, model.events(),
                                      model.integration_options(), model.observer());
    }
    seg.t = seg.integrated.t;
    end.t = seg.t;
    end.y = stepper.y();
    if (is_failure(seg.integrated.reason)) {
      model.on_failure(seg, end.y, stepper);
      break;
    }
    if (model.on_segment_end(seg, end.y, stepper) == Next::kStop) break;
    model.on_restart();
    restart(model, stepper, end.t, end.y);
  }
  return end;
}

}  // namespace pronk::run
