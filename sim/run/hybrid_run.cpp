#include "sim/run/hybrid_run.hpp"

#include <sstream>

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

HybridEnd run_hybrid(HybridModel& model, ode::Stepper& stepper, double t0, const ode::Vec& y0) {
  HybridEnd end{t0, y0};
  stepper.reset(model.system(), t0, y0);
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
    stepper.reset(model.system(), end.t, end.y);
  }
  return end;
}

}  // namespace pronk::run
