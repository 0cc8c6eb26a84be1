#include "sim/reduced/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <span>
#include <utility>

#include "sim/control/stance_planner.hpp"
#include "sim/reduced/rigid_body.hpp"
#include "sim/reduced/run_limits.hpp"
#include "sim/reduced/run_record.hpp"
#include "sim/run/hybrid_run.hpp"

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

/// One reduced-model run on the hybrid loop: flight and stance segments, touchdown
/// (controller: an impulse or a stance of constant leg forces), apex, stance end,
/// disturbances and falls.
class ReducedRun final : public run::HybridModel {
 public:
  enum { kTouchdown = 0, kApex = 1, kFallLow = 2, kFallTilt = 3 };

  ReducedRun(const scene::Scene& scene, const RunOptions& options)
      : scene_(scene),
        belief_(scene::controller_view(scene)),
        options_(options),
        pulse_(scene.model == scene::ModelKind::kPulse),
        model_(scene, /*impulse_quadrature=*/pulse_),
        rhs_(model_),
        body_controller_(scene.controller, scene.gravity, scene.legs.length, !scene.legs.body_only,
                         !model_.layout.quaternion, pulse_ ? scene.pulse.duration : 0.0),
        leg_controller_(control::make_leg_controller(belief_)),
        touchdown_(scene.legs.length),
        fall_low_(scene.simulation.fall_min_height),
        fall_tilt_(model_.layout, scene.simulation.fall_max_tilt),
        flight_events_{&touchdown_, &apex_, &fall_low_, &fall_tilt_},
        stance_events_{&apex_, &fall_low_, &fall_tilt_},
        sampler_(model_, scene, &result.trajectory),
        angle_watch_(model_.layout, options.record_trajectory ? &sampler_ : nullptr),
        energy_scale_(scene.body.mass * scene.gravity *
                      std::max(scene.controller.hop_height, 1e-3)),
        pending_touchdown_(options.start_at_touchdown) {}

  const RigidBodyModel& model() const { return model_; }
  long touchdowns() const { return touchdowns_; }
  long touchdown_events() const { return touchdown_events_; }
  /// Closes the stride in progress; t_next < 0: the run ended before the next touchdown.
  void finish_stride(double t_next) {
    if (!have_stride_) return;
    close_stride(current_, t_next);
    if (options_.record_strides) result.strides.push_back(current_);
    have_stride_ = false;
  }

  const ode::OdeSystem& system() const override { return rhs_; }
  const ode::SolverOptions& integration_options() const override {
    return scene_.simulation.solver;
  }
  void start(const ode::Stepper&, const ode::Vec& y) override {
    flight_energy_ = model_.energy(y);
    if (options_.record_trajectory) sampler_.start(y);
    if (small_angle() && y.segment<3>(6).cwiseAbs().maxCoeff() > kSmallAngleLimit) {
      angle_watch_.exceeded = true;  // the initial attitude already leaves the range
    }
  }
  /// A run the fixed-step rule refuses (run_limits.hpp): `diverged` at t = 0 with the reason,
  /// the initial sample kept.
  run::HybridEnd refuse(ode::Stepper& stepper, const ode::Vec& y0, std::string reason) {
    stepper.reset(rhs_, 0.0, y0);
    start(stepper, y0);
    result.status = RunStatus::kDiverged;
    result.reason = std::move(reason);
    return {0.0, y0};
  }
  bool take_pending_event() override { return std::exchange(pending_touchdown_, false); }
  double segment_end(double) const override {
    double t_target = scene_.simulation.duration;
    if (next_disturbance_ < scene_.disturbances.size()) {
      t_target = std::min(t_target, scene_.disturbances[next_disturbance_].time);
    }
    if (stance_) t_target = std::min(t_target, stance_end_);
    return t_target;
  }
  std::span<const ode::EventFunction* const> events() const override {
    return stance_ ? std::span<const ode::EventFunction* const>(stance_events_)
                   : std::span<const ode::EventFunction* const>(flight_events_);
  }
  ode::StepObserver* observer() override {
    return small_angle()                ? &angle_watch_
           : options_.record_trajectory ? static_cast<ode::StepObserver*>(&sampler_)
                                        : nullptr;
  }
  void on_failure(const run::Segment& seg, const ode::Vec&, const ode::Stepper& st) override {
    count_angle_warning();
    result.status = RunStatus::kDiverged;
    result.reason = run::failure_reason(seg, st, scene_.simulation.solver);
  }
  run::Next on_segment_end(const run::Segment& seg, ode::Vec& y, const ode::Stepper&) override {
    count_angle_warning();
    const double t = seg.t;
    const int event = seg.pending        ? kTouchdown
                      : seg.event() >= 0 ? (stance_ ? seg.event() + 1 : seg.event())
                                         : -1;
    if (model_.layout.quaternion) {
      const double n = Eigen::Vector4d(y[6], y[7], y[8], y[9]).norm();
      result.monitors.max_quaternion_norm_error =
          std::max(result.monitors.max_quaternion_norm_error, std::abs(n - 1.0));
      model_.normalize(y);
    }
    switch (event) {
      case kFallLow:
        return fall(fell_low_reason(scene_, t));
      case kFallTilt:
        return fall(tilted_reason(scene_, t));
      case kApex:
        if (!stance_ && have_stride_ && !current_.has_apex) {
          current_.has_apex = true;
          current_.apex_height = y[2];
        }
        return run::Next::kContinue;
      case kTouchdown:
        return touchdown(t, y);
      default:
        return scheduled_time(t, y);
    }
  }

  RunResult result;

 private:
  bool small_angle() const { return !model_.layout.quaternion; }
  /// Counted once per integration segment (flight, stance) in which it happened.
  void count_angle_warning() {
    if (!angle_watch_.exceeded) return;
    ++result.warnings["small_angle_range_exceeded"];
    angle_watch_.exceeded = false;
  }
  run::Next fall(std::string reason) {
    result.status = RunStatus::kFell;
    result.reason = std::move(reason);
    return run::Next::kStop;
  }
  /// |Delta E| over the flight ending at y relative to m g h; without gravity (no potential
  /// energy, no height scale) relative to the flight's own energy, its kinetic energy (a
  /// body at rest in zero gravity stays exactly at rest: 0).
  double flight_energy_drift(const ode::Vec& y) const {
    const double change = std::abs(model_.energy(y) - flight_energy_);
    const double scale = energy_scale_ > 0.0 ? energy_scale_ : std::abs(flight_energy_);
    return change > 0.0 ? change / scale : 0.0;
  }
  run::Next touchdown(double t, ode::Vec& y);
  run::Next scheduled_time(double t, ode::Vec& y);
  void impulse(const control::StancePlan& plan, const BodyState& s, ode::Vec& y);

  const scene::Scene& scene_;
  /// The scene as the controller sees it: the robot's nominal numbers when a robust-design
  /// scenario perturbed the robot (scene::ControllerModel).
  const scene::Scene belief_;
  const RunOptions& options_;
  const bool pulse_;
  const RigidBodyModel model_;
  RigidBodyRhs rhs_;
  control::PdBodyController body_controller_;
  std::unique_ptr<control::LegController> leg_controller_;
  HeightEvent touchdown_;
  ApexEvent apex_;
  HeightEvent fall_low_;
  TiltEvent fall_tilt_;
  const ode::EventFunction* flight_events_[4];
  const ode::EventFunction* stance_events_[3];
  Sampler sampler_;
  SmallAngleWatch angle_watch_;
  const double energy_scale_;
  bool pending_touchdown_;

  StrideRecord current_;  // the stride in progress
  bool have_stride_ = false;
  long touchdowns_ = 0;        // strides begun
  long touchdown_events_ = 0;  // located touchdowns, including one that ends the run
  bool stance_ = false;
  double stance_end_ = 0.0;
  control::StancePlan plan_;
  size_t next_disturbance_ = 0;
  double flight_energy_ = 0.0;
};

run::Next ReducedRun::touchdown(double t, ode::Vec& y) {
  // Flight energy is conserved (torque-free ballistic flight): monitor it.
  result.monitors.max_flight_energy_drift =
      std::max(result.monitors.max_flight_energy_drift, flight_energy_drift(y));
  result.monitors.max_event_residual =
      std::max(result.monitors.max_event_residual, std::abs(y[2] - scene_.legs.length));
  finish_stride(t);
  ++touchdown_events_;
  if (touchdowns_ >= scene_.simulation.max_strides) return run::Next::kStop;
  const BodyState s = model_.decode(y);
  const control::StanceContext ctx{belief_, body_controller_, *leg_controller_};
  plan_ = control::plan_stance(ctx, touchdowns_, t, s);
  current_ = open_stride(touchdowns_++, t, s, plan_, scene_, result.warnings);
  have_stride_ = true;
  current_.stance_duration = plan_.duration;
  if (plan_.duration <= 0.0) {
    impulse(plan_, s, y);
    return run::Next::kContinue;
  }
  stance_ = true;
  stance_end_ = t + plan_.duration;
  // The legs push at their own force limit for the planned time (max_force mode): a limit
  // the controller does not know scales the pushes.
  const double gain = scene_.pulse.mode == scene::PulseMode::kMaxForce
                          ? scene_.pulse.max_force / belief_.pulse.max_force
                          : 1.0;
  rhs_.set_leg_load(gain * plan_.net_force_body, gain * plan_.net_moment_body);
  y.segment<3>(model_.layout.quadrature_index()).setZero();
  double peak = 0.0;
  for (const auto& f : plan_.leg_force) peak = std::max(peak, f.norm());
  current_.peak_leg_force = peak;
  sampler_.stance = true;
  sampler_.force_body = plan_.net_force_body;
  return run::Next::kContinue;
}

/// Impulse model (or nothing to push): instantaneous momentum change.
void ReducedRun::impulse(const control::StancePlan& plan, const BodyState& s, ode::Vec& y) {
  Vector3d P_body = Vector3d::Zero(), H_body = Vector3d::Zero();
  if (scene_.legs.body_only) {
    P_body = plan.P_body;
    H_body = plan.H_body;
  } else {
    for (size_t i = 0; i < plan.leg_impulse.size(); ++i) {
      P_body += plan.leg_impulse[i];
      H_body += scene_.legs.hips[i].cross(plan.leg_impulse[i]);
    }
  }
  current_.P_delivered = s.rotation * P_body;
  current_.H_delivered = H_body;
  model_.apply_impulse(y, current_.P_delivered, H_body);
  flight_energy_ = model_.energy(y);
}

/// Reached the segment's end: stance end, a disturbance, or the end of the run.
run::Next ReducedRun::scheduled_time(double t, ode::Vec& y) {
  if (stance_ && t >= stance_end_) {
    stance_ = false;
    rhs_.set_leg_load(Vector3d::Zero(), Vector3d::Zero());
    if (have_stride_) {
      current_.P_delivered = y.segment<3>(model_.layout.quadrature_index());
      current_.H_delivered = plan_.net_moment_body * plan_.duration;
    }
    sampler_.stance = false;
    flight_energy_ = model_.energy(y);
  }
  while (next_disturbance_ < scene_.disturbances.size() &&
         scene_.disturbances[next_disturbance_].time <= t) {
    const auto& d = scene_.disturbances[next_disturbance_++];
    model_.apply_impulse(y, d.linear_impulse, d.angular_impulse);
    if (!stance_) flight_energy_ = model_.energy(y);
  }
  return t >= scene_.simulation.duration ? run::Next::kStop : run::Next::kContinue;
}

}  // namespace

RunResult simulate(const scene::Scene& scene, const RunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  require_memory_limits(scene.simulation, options.record_trajectory, options.record_strides);
  ReducedRun hybrid(scene, options);
  const RigidBodyModel& model = hybrid.model();
  auto stepper = ode::make_stepper(scene.simulation.solver, model.layout.size());
  ode::Vec y0(model.layout.size());
  model.initial_state(scene, y0);
  const auto too_long = fixed_step_breach(scene, scene.simulation.solver);
  const run::HybridEnd end = too_long ? hybrid.refuse(*stepper, y0, too_long->reason())
                                      : run::run_hybrid(hybrid, *stepper, 0.0, y0);
  hybrid.finish_stride(-1.0);  // last stride: no next touchdown, stride time 0
  RunResult& result = hybrid.result;
  finish_run(result, end.t, model.decode(end.y), hybrid.touchdowns(), scene);
  result.cost.solver = stepper->counters();
  result.cost.touchdowns = hybrid.touchdown_events();
  result.cost.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return std::move(result);
}

}  // namespace pronk::reduced
