// The hybrid run loop on a bouncing ball: events, state changes at events, scheduled
// times, restarts, pending events and failures, against closed-form bounce times.
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "sim/run/hybrid_run.hpp"

namespace hybrid_run_test {

using pronk::ode::Vec;
namespace run = pronk::run;
namespace ode = pronk::ode;

constexpr double kG = 9.81;  // [m/s^2]

/// z'' = -g as (z, v).
class Fall final : public ode::OdeSystem {
 public:
  int dimension() const override { return 2; }
  void rhs(double, const Vec& y, Vec& dydt) const override {
    dydt[0] = y[1];
    dydt[1] = -kG;
  }
};

class Ground final : public ode::EventFunction {
 public:
  double value(double, const Vec& y) const override { return y[0]; }
  int direction() const override { return -1; }
};

/// Stops the integration once the step count reaches `limit`.
class StepLimit final : public ode::StepObserver {
 public:
  void on_step(const ode::Stepper&, double) override { ++steps; }
  bool stop_requested() const override { return limit > 0 && steps >= limit; }
  long steps = 0;
  long limit = 0;
};

/// A ball dropped from 1 m bouncing with restitution e; a kick (v += kick) at t_kick.
class Ball final : public run::HybridModel {
 public:
  const ode::OdeSystem& system() const override { return fall_; }
  const ode::SolverOptions& integration_options() const override { return options; }
  void start(const ode::Stepper&, const Vec&) override { ++starts; }
  bool take_pending_event() override { return std::exchange(pending, false); }
  double segment_end(double t) const override { return t < t_kick ? t_kick : t_end; }
  std::span<const ode::EventFunction* const> events() const override { return events_; }
  ode::StepObserver* observer() override { return &steps; }
  void on_failure(const run::Segment& s, const Vec&, const ode::Stepper&) override {
    failure = s.integrated.reason;
  }
  run::Next on_segment_end(const run::Segment& s, Vec& y, const ode::Stepper&) override {
    if (s.pending) {
      ++pending_handled;
      return run::Next::kContinue;
    }
    if (s.event() == 0) {
      bounces.push_back(s.t);
      y[1] = -restitution * y[1];
      return bounces.size() >= max_bounces ? run::Next::kStop : run::Next::kContinue;
    }
    if (s.t >= t_end) return run::Next::kStop;
    y[1] += kick;
    return run::Next::kContinue;
  }
  void on_restart() override { ++restarts; }

  ode::SolverOptions options;
  double restitution = 0.5, t_kick = 1e9, kick = 0.0, t_end = 10.0;
  size_t max_bounces = 4;
  bool pending = false;
  int starts = 0, restarts = 0, pending_handled = 0;
  std::vector<double> bounces;
  ode::StopReason failure = ode::StopReason::kReachedEnd;
  StepLimit steps;

 private:
  Fall fall_;
  Ground ground_;
  const ode::EventFunction* events_[1] = {&ground_};
};

}  // namespace hybrid_run_test

TEST_CASE("run_hybrid: bounces at the closed-form times, state changed at each event", "[run]") {
  hybrid_run_test::Ball ball;
  ball.options.rtol = ball.options.atol = 1e-10;
  auto stepper = pronk::ode::make_stepper(ball.options, 2);
  pronk::ode::Vec y0(2);
  y0 << 1.0, 0.0;
  const pronk::run::HybridEnd end = pronk::run::run_hybrid(ball, *stepper, 0.0, y0);
  // Drop from 1 m: first impact at sqrt(2/g), then flights of 2 v_k / g, v_k halved each time.
  const double v0 = std::sqrt(2.0 * hybrid_run_test::kG);
  double t = v0 / hybrid_run_test::kG, v = v0;
  REQUIRE(ball.bounces.size() == 4);
  for (double tb : ball.bounces) {
    CHECK(tb == Approx(t).epsilon(1e-9));
    v *= 0.5;
    t += 2.0 * v / hybrid_run_test::kG;
  }
  CHECK(end.t == ball.bounces.back());
  CHECK(end.y[1] == Approx(0.5 * 0.5 * 0.5 * 0.5 * v0).epsilon(1e-8));  // changed state kept
  CHECK(ball.starts == 1);
  CHECK(ball.restarts == 3);
  CHECK(stepper->counters().events == 4);
}

TEST_CASE("run_hybrid: scheduled times, a pending event and an observer stop", "[run]") {
  SECTION("a kick at a scheduled time and the run's end") {
    hybrid_run_test::Ball ball;
    ball.max_bounces = 100;
    ball.t_kick = 0.2;
    ball.kick = 1.0;
    ball.t_end = 0.3;
    ball.pending = true;
    auto stepper = pronk::ode::make_stepper(ball.options, 2);
    pronk::ode::Vec y0(2);
    y0 << 1.0, 0.0;
    const pronk::run::HybridEnd end = pronk::run::run_hybrid(ball, *stepper, 0.0, y0);
    CHECK(ball.pending_handled == 1);
    CHECK(ball.bounces.empty());
    CHECK(end.t == 0.3);
    CHECK(end.y[1] == Approx(-hybrid_run_test::kG * 0.3 + 1.0).epsilon(1e-9));
  }
  SECTION("the observer stops the integration: on_failure, no restart") {
    hybrid_run_test::Ball ball;
    ball.steps.limit = 3;
    ball.options.method = pronk::ode::Method::kRk4;
    ball.options.h_fixed = 1e-2;
    auto stepper = pronk::ode::make_stepper(ball.options, 2);
    pronk::ode::Vec y0(2);
    y0 << 1.0, 0.0;
    const pronk::run::HybridEnd end = pronk::run::run_hybrid(ball, *stepper, 0.0, y0);
    CHECK(ball.failure == pronk::ode::StopReason::kStopped);
    CHECK(end.t == Approx(0.03));
    CHECK(ball.restarts == 0);
  }
}
