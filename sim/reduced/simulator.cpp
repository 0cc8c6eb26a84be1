#include "sim/reduced/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "sim/control/stance_planner.hpp"
#include "sim/reduced/rigid_body.hpp"

namespace pronk::reduced {

std::string_view to_string(RunStatus s) {
  switch (s) {
    case RunStatus::kCompleted:
      return "completed";
    case RunStatus::kFell:
      return "fell";
    case RunStatus::kDiverged:
      return "diverged";
  }
  return "?";
}

namespace {

using Eigen::Vector3d;

/// Touchdown: the CoM falls through the leg length.
class HeightEvent final : public ode::EventFunction {
 public:
  explicit HeightEvent(double level) : level_(level) {}
  double value(double, const Vec& y) const override { return y[2] - level_; }

 private:
  double level_;
};

/// Apex: vertical velocity falls through zero.
class ApexEvent final : public ode::EventFunction {
 public:
  double value(double, const Vec& y) const override { return y[5]; }
};

/// Fall by tilt: the body z axis's vertical component falls through cos(max tilt).
class TiltEvent final : public ode::EventFunction {
 public:
  TiltEvent(const Layout& layout, double max_tilt)
      : layout_(layout), cos_max_(std::cos(max_tilt)) {}
  double value(double, const Vec& y) const override {
    double up = 0.0;
    if (layout_.quaternion) {
      const double w = y[6], x = y[7], yy = y[8], z = y[9];
      up = (w * w - x * x - yy * yy + z * z) / (w * w + x * x + yy * yy + z * z);
    } else {
      up = math::euler_to_matrix(y.segment<3>(6), math::EulerSet::k123)(2, 2);
    }
    return up - cos_max_;
  }

 private:
  Layout layout_;
  double cos_max_;
};

/// Samples the trajectory on a fixed grid from the dense output.
class Sampler final : public ode::StepObserver {
 public:
  Sampler(const RigidBodyModel& model, const scene::Scene& scene, std::vector<Sample>* out)
      : model_(model), scene_(scene), out_(out), y_(model.layout.size()) {}
  void on_step(const ode::Stepper& stepper, double t_stop) override {
    while (next_ <= t_stop + 1e-12 * std::max(1.0, t_stop)) {
      stepper.dense(std::min(next_, stepper.t()), y_);
      record(next_, y_);
      next_ = scene_.simulation.sample_interval * static_cast<double>(++count_);
    }
  }
  void record(double t, const Vec& y) {
    const BodyState s = model_.decode(y);
    Sample smp;
    smp.t = t;
    smp.position = s.position;
    smp.velocity = s.velocity;
    smp.euler123 = s.euler123;
    smp.omega = s.omega;
    smp.setpoint = scene_.controller.setpoint_position + scene_.controller.setpoint_velocity * t;
    smp.stance = stance;
    smp.leg_force_world = stance ? Vector3d(s.rotation * force_body) : Vector3d::Zero();
    out_->push_back(smp);
  }
  /// Records the initial state (t = 0).
  void start(const Vec& y) {
    record(0.0, y);
    next_ = scene_.simulation.sample_interval * static_cast<double>(++count_);
  }
  bool stance = false;
  Vector3d force_body = Vector3d::Zero();

 private:
  const RigidBodyModel& model_;
  const scene::Scene& scene_;
  std::vector<Sample>* out_;
  Vec y_;
  double next_ = 0.0;
  long count_ = 0;
};

/// Largest |angle| the seed's small-angle formulation is trusted with [rad]: it integrates
/// the 1-2-3 angles as if they were integrals of the body rates, an error of first order in
/// the angles.
constexpr double kSmallAngleLimit = 15.0 * M_PI / 180.0;

/// Watches every accepted step of the small-angle formulation for angles outside
/// +-kSmallAngleLimit (the run then carries the warning "small_angle_range_exceeded"), and
/// forwards the step to the next observer (the sampler), if any.
class SmallAngleWatch final : public ode::StepObserver {
 public:
  SmallAngleWatch(const Layout& layout, ode::StepObserver* next) : layout_(layout), next_(next) {}
  void on_step(const ode::Stepper& stepper, double t_stop) override {
    if (!layout_.quaternion && stepper.y().segment<3>(6).cwiseAbs().maxCoeff() > kSmallAngleLimit) {
      exceeded = true;
    }
    if (next_) next_->on_step(stepper, t_stop);
  }
  bool exceeded = false;  ///< in the current integration segment

 private:
  Layout layout_;
  ode::StepObserver* next_;
};

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

}  // namespace

RunResult simulate(const scene::Scene& scene, const RunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  RunResult result;
  const bool pulse = scene.model == scene::ModelKind::kPulse;
  const RigidBodyModel model(scene, /*impulse_quadrature=*/pulse);
  const Layout& L = model.layout;
  RigidBodyRhs rhs(model);
  const bool small_angle = !L.quaternion;
  control::PdBodyController body_controller(scene.controller, scene.gravity, scene.legs.length,
                                            !scene.legs.body_only, small_angle,
                                            pulse ? scene.pulse.duration : 0.0);
  const auto leg_controller = control::make_leg_controller(scene);
  const control::StanceContext ctx{scene, body_controller, *leg_controller};

  const auto& sim = scene.simulation;
  auto stepper = ode::make_stepper(sim.solver, L.size());
  Vec y(L.size());
  model.initial_state(scene, y);

  HeightEvent touchdown(scene.legs.length);
  ApexEvent apex;
  HeightEvent fall_low(sim.fall_min_height);
  TiltEvent fall_tilt(L, sim.fall_max_tilt);
  const ode::EventFunction* flight_events[] = {&touchdown, &apex, &fall_low, &fall_tilt};
  const ode::EventFunction* stance_events[] = {&apex, &fall_low, &fall_tilt};
  enum { kTouchdown = 0, kApex = 1, kFallLow = 2, kFallTilt = 3 };

  Sampler sampler(model, scene, &result.trajectory);
  ode::StepObserver* sampler_or_null = options.record_trajectory ? &sampler : nullptr;
  SmallAngleWatch angle_watch(L, sampler_or_null);
  ode::StepObserver* observer = small_angle ? &angle_watch : sampler_or_null;
  std::vector<StrideRecord>& strides = result.strides;
  StrideRecord current;  // the stride in progress
  bool have_stride = false;
  long touchdowns = 0;        // strides begun
  long touchdown_events = 0;  // located touchdowns, including one that ends the run

  double t = 0.0;
  bool stance = false;
  double stance_end = 0.0;
  control::StancePlan plan;
  size_t next_disturbance = 0;
  const double energy_scale =
      scene.body.mass * scene.gravity * std::max(scene.controller.hop_height, 1e-3);
  double flight_energy = model.energy(y);

  // Closes the stride in progress; t_next < 0: the run ended before the next touchdown.
  auto finish_stride = [&](double t_next) {
    if (!have_stride) return;
    if (t_next > current.t_touchdown) {
      current.stride_time = t_next - current.t_touchdown;
      current.duty_cycle = current.stance_duration / current.stride_time;
    }
    if (options.record_strides) strides.push_back(current);
    have_stride = false;
  };
  auto end_run = [&](RunStatus status, std::string reason) {
    result.status = status;
    result.reason = std::move(reason);
  };

  stepper->reset(rhs, t, y);
  if (options.record_trajectory) sampler.start(y);
  if (small_angle && y.segment<3>(6).cwiseAbs().maxCoeff() > kSmallAngleLimit) {
    angle_watch.exceeded = true;  // the initial attitude already leaves the range
  }

  bool pending_touchdown = options.start_at_touchdown;
  bool running = true;
  while (running) {
    double t_target = sim.duration;
    if (next_disturbance < scene.disturbances.size()) {
      t_target = std::min(t_target, scene.disturbances[next_disturbance].time);
    }
    if (stance) t_target = std::min(t_target, stance_end);
    std::span<const ode::EventFunction* const> events =
        stance ? std::span<const ode::EventFunction* const>(stance_events)
               : std::span<const ode::EventFunction* const>(flight_events);
    ode::IntegrateResult r;
    const bool forced_touchdown = pending_touchdown;
    pending_touchdown = false;
    if (forced_touchdown) {
      r.reason = ode::StopReason::kReachedEnd;
      r.t = t;
    } else if (t_target > t) {
      r = ode::integrate(rhs, *stepper, t_target, events, sim.solver, observer);
    } else {
      r.reason = ode::StopReason::kReachedEnd;
      r.t = t;
    }
    t = r.t;
    y = stepper->y();
    if (angle_watch.exceeded) {
      // Counted once per integration segment (flight, stance) in which it happened.
      ++result.warnings["small_angle_range_exceeded"];
      angle_watch.exceeded = false;
    }
    const int event = forced_touchdown ? kTouchdown
                      : r.reason == ode::StopReason::kEvent
                          ? (stance ? r.event_index + 1 : r.event_index)
                          : -1;
    switch (r.reason) {
      case ode::StopReason::kStepSizeCollapse:
        end_run(RunStatus::kDiverged, "step-size collapse at t = " + fmt(t) + " s");
        running = false;
        continue;
      case ode::StopReason::kNonFinite:
        end_run(RunStatus::kDiverged, "non-finite state at t = " + fmt(t) + " s");
        running = false;
        continue;
      case ode::StopReason::kMaxSteps:
        end_run(RunStatus::kDiverged,
                sim.solver.step_limit_reason(
                    stepper->counters().steps_accepted + stepper->counters().steps_rejected, t));
        running = false;
        continue;
      case ode::StopReason::kCrawling:
        end_run(RunStatus::kDiverged, sim.solver.crawl_reason(r.attempts, t - r.t_start, t));
        running = false;
        continue;
      default:
        break;
    }
    if (L.quaternion) {
      const double n = Eigen::Vector4d(y[6], y[7], y[8], y[9]).norm();
      result.monitors.max_quaternion_norm_error =
          std::max(result.monitors.max_quaternion_norm_error, std::abs(n - 1.0));
      model.normalize(y);
    }
    if (event == kFallLow) {
      end_run(RunStatus::kFell,
              "CoM fell below " + fmt(sim.fall_min_height) + " m at t = " + fmt(t) + " s");
      break;
    }
    if (event == kFallTilt) {
      end_run(RunStatus::kFell, "body tilted past " + fmt(sim.fall_max_tilt * 180.0 / M_PI) +
                                    " deg at t = " + fmt(t) + " s");
      break;
    }
    if (event == kApex) {
      if (!stance && have_stride && !current.has_apex) {
        current.has_apex = true;
        current.apex_height = y[2];
      }
    } else if (event == kTouchdown) {
      // Flight energy is conserved (torque-free ballistic flight): monitor it.
      result.monitors.max_flight_energy_drift =
          std::max(result.monitors.max_flight_energy_drift,
                   std::abs(model.energy(y) - flight_energy) / energy_scale);
      result.monitors.max_event_residual =
          std::max(result.monitors.max_event_residual, std::abs(y[2] - scene.legs.length));
      finish_stride(t);
      ++touchdown_events;
      if (touchdowns >= sim.max_strides) {
        running = false;
        break;
      }
      const BodyState s = model.decode(y);
      plan = control::plan_stance(ctx, touchdowns, t, s);
      current = StrideRecord{};
      have_stride = true;
      current.index = touchdowns++;
      current.t_touchdown = t;
      current.position = s.position;
      current.velocity = s.velocity;
      current.euler123 = s.euler123;
      current.omega = s.omega;
      current.setpoint =
          scene.controller.setpoint_position + scene.controller.setpoint_velocity * t;
      current.P_requested = plan.command.P_world;
      current.H_requested = plan.command.H_body;
      current.gravity_compensation = plan.gravity_compensation;
      current.stance_duration = plan.duration;
      current.active_legs = plan.active_legs;
      current.allocation = plan.allocation_status;
      if (plan.allocation_status != control::AllocationStatus::kOk) {
        ++result.warnings[plan.allocation_status == control::AllocationStatus::kLimited
                              ? "allocation_limited"
                              : "allocation_infeasible"];
      }
      if (plan.duration <= 0.0) {
        // Impulse model (or nothing to push): instantaneous momentum change.
        Vector3d P_body = Vector3d::Zero(), H_body = Vector3d::Zero();
        if (scene.legs.body_only) {
          P_body = plan.P_body;
          H_body = plan.H_body;
        } else {
          for (size_t i = 0; i < plan.leg_impulse.size(); ++i) {
            P_body += plan.leg_impulse[i];
            H_body += scene.legs.hips[i].cross(plan.leg_impulse[i]);
          }
        }
        current.P_delivered = s.rotation * P_body;
        current.H_delivered = H_body;
        model.apply_impulse(y, current.P_delivered, H_body);
        flight_energy = model.energy(y);
      } else {
        stance = true;
        stance_end = t + plan.duration;
        rhs.set_leg_load(plan.net_force_body, plan.net_moment_body);
        y.segment<3>(L.quadrature_index()).setZero();
        double peak = 0.0;
        for (const auto& f : plan.leg_force) peak = std::max(peak, f.norm());
        current.peak_leg_force = peak;
        sampler.stance = true;
        sampler.force_body = plan.net_force_body;
      }
    } else {
      // Reached t_target: stance end, a disturbance, or the end of the run.
      if (stance && t >= stance_end) {
        stance = false;
        rhs.set_leg_load(Vector3d::Zero(), Vector3d::Zero());
        if (have_stride) {
          current.P_delivered = y.segment<3>(L.quadrature_index());
          current.H_delivered = plan.net_moment_body * plan.duration;
        }
        sampler.stance = false;
        flight_energy = model.energy(y);
      }
      while (next_disturbance < scene.disturbances.size() &&
             scene.disturbances[next_disturbance].time <= t) {
        const auto& d = scene.disturbances[next_disturbance++];
        model.apply_impulse(y, d.linear_impulse, d.angular_impulse);
        if (!stance) flight_energy = model.energy(y);
      }
      if (t >= sim.duration) running = false;
    }
    if (running) stepper->reset(rhs, t, y);
  }
  finish_stride(-1.0);  // last stride: no next touchdown, stride time 0

  result.t_end = t;
  const BodyState s = model.decode(y);
  result.final_position = s.position;
  result.final_velocity = s.velocity;
  result.final_euler123 = s.euler123;
  result.final_omega = s.omega;
  result.final_attitude = s.attitude;
  if (result.status == RunStatus::kCompleted) {
    result.reason = touchdowns > sim.max_strides - 1 && t < sim.duration
                        ? "reached " + std::to_string(sim.max_strides) + " strides"
                        : "reached t = " + fmt(t) + " s";
  }
  result.cost.solver = stepper->counters();
  result.cost.touchdowns = touchdown_events;
  result.cost.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace pronk::reduced
