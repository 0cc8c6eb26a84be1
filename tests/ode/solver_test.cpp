// Generic tests of every ODE method against closed-form references.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "sim/ode/solver.hpp"

namespace {

using pronk::ode::EventFunction;
using pronk::ode::integrate;
using pronk::ode::IntegrateResult;
using pronk::ode::make_stepper;
using pronk::ode::Method;
using pronk::ode::OdeSystem;
using pronk::ode::SolverOptions;
using pronk::ode::StepObserver;
using pronk::ode::Stepper;
using pronk::ode::StopReason;
using pronk::ode::Vec;

constexpr double kGravity = 9.81;  // [m/s^2]

/// y' = -2 t y^2, y(0) = 1: y(t) = 1 / (1 + t^2).
class Riccati final : public OdeSystem {
 public:
  int dimension() const override { return 1; }
  void rhs(double t, const Vec& y, Vec& dydt) const override { dydt[0] = -2.0 * t * y[0] * y[0]; }
  static double exact(double t) { return 1.0 / (1.0 + t * t); }
};

/// x'' = -x as (x, v); x(0) = 1, v(0) = 0: x = cos t, v = -sin t.
class Oscillator final : public OdeSystem {
 public:
  int dimension() const override { return 2; }
  void rhs(double, const Vec& y, Vec& dydt) const override {
    dydt[0] = y[1];
    dydt[1] = -y[0];
  }
};

/// Ballistic flight (z [m], v [m/s]) under gravity.
class Ballistic final : public OdeSystem {
 public:
  int dimension() const override { return 2; }
  void rhs(double, const Vec& y, Vec& dydt) const override {
    dydt[0] = y[1];
    dydt[1] = -kGravity;
  }
};

/// y' = y^2, y(0) = 1: blows up at t = 1.
class BlowUp final : public OdeSystem {
 public:
  int dimension() const override { return 1; }
  void rhs(double, const Vec& y, Vec& dydt) const override { dydt[0] = y[0] * y[0]; }
};

/// Height z - level [m] (falling by default).
class HeightEvent final : public EventFunction {
 public:
  explicit HeightEvent(double level, int dir = -1) : level_(level), dir_(dir) {}
  double value(double, const Vec& y) const override { return y[0] - level_; }
  int direction() const override { return dir_; }

 private:
  double level_;
  int dir_;
};

/// Vertical velocity v [m/s]; falling crossing = apex.
class ApexEvent final : public EventFunction {
 public:
  double value(double, const Vec& y) const override { return y[1]; }
};

/// Least-squares slope of log(err) over log(h).
double fit_order(const std::vector<double>& h, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Options making every method take steps of exactly h [s]; DOPRI5 is forced
/// to fixed steps by huge tolerances (it never rejects and is capped by h_max).
SolverOptions fixed_step_options(Method m, double h) {
  SolverOptions o;
  o.method = m;
  o.h_fixed = h;
  if (m == Method::kDopri5) {
    o.rtol = o.atol = 1e30;
    o.h_max = o.h_initial = h;
    o.h_min = 0.0;
  }
  return o;
}

/// Theoretical order and the step counts used to measure it on [0, 2].
struct OrderCase {
  double order;
  std::vector<int> steps;
};

OrderCase order_case(Method m) {
  switch (m) {
    case Method::kEuler:
      return {1.0, {200, 400, 800, 1600}};
    case Method::kRk2:
      return {2.0, {50, 100, 200, 400}};
    case Method::kRk4:
      return {4.0, {20, 40, 80, 160}};
    case Method::kDopri5:
      return {5.0, {40, 80, 160}};
    case Method::kRodas4:  // stiff solvers: rosenbrock_test.cpp, radau5_test.cpp, cvode_test.cpp
    case Method::kRadau5:
    case Method::kCvodeBdf:
    case Method::kVerlet:  // mechanical systems only: verlet_test.cpp
      break;
  }
  return {};
}

/// Records the largest error of dense output at each step's midpoint.
class MidpointError final : public StepObserver {
 public:
  void on_step(const Stepper& s, double t_stop) override {
    const double tm = 0.5 * (s.t_prev() + t_stop);
    s.dense(tm, y_);
    max_err = std::max(max_err, std::abs(y_[0] - Riccati::exact(tm)));
    ++calls;
  }
  double max_err = 0.0;
  long calls = 0;

 private:
  Vec y_ = Vec(1);
};

/// Number of f calls per accepted or rejected step.
long stages(Method m) {
  switch (m) {
    case Method::kEuler:
      return 1;
    case Method::kRk2:
      return 2;
    case Method::kRk4:
      return 4;
    case Method::kDopri5:
      return 6;
    case Method::kRodas4:  // not part of this generic suite
    case Method::kRadau5:
    case Method::kCvodeBdf:
    case Method::kVerlet:
      break;
  }
  return 0;
}

}  // namespace

TEST_CASE("ode: order of convergence of step and dense output", "[ode]") {
  const Method m = GENERATE(Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5);
  INFO("method " << to_string(m));
  const OrderCase oc = order_case(m);
  const Riccati sys;
  std::vector<double> hs, err_end, err_mid;
  for (int n : oc.steps) {
    const double h = 2.0 / n;
    auto s = make_stepper(fixed_step_options(m, h), 1);
    s->reset(sys, 0.0, Vec::Ones(1));
    MidpointError obs;
    const IntegrateResult r = integrate(sys, *s, 2.0, {}, fixed_step_options(m, h), &obs);
    REQUIRE(r.reason == StopReason::kReachedEnd);
    REQUIRE(s->t() == 2.0);
    CHECK(s->counters().steps_accepted == n);
    CHECK(s->counters().steps_rejected == 0);
    CHECK(obs.calls == n);
    hs.push_back(h);
    err_end.push_back(std::abs(s->y()[0] - Riccati::exact(2.0)));
    err_mid.push_back(obs.max_err);
  }
  const double p = fit_order(hs, err_end);
  const double p_dense = fit_order(hs, err_mid);
  INFO("order " << p << ", dense order " << p_dense);
  CHECK(p == Approx(oc.order).margin(m == Method::kDopri5 ? 0.3 : 0.2));
  // Hermite / contd5 dense output must not spoil the order (DOPRI5's is 4th order).
  if (m == Method::kDopri5) {
    CHECK(p_dense > 3.7);
  } else {
    CHECK(p_dense == Approx(oc.order).margin(0.2));
  }
}

TEST_CASE("ode: DOPRI5 adaptive accuracy on the oscillator", "[ode]") {
  SolverOptions o;
  o.rtol = o.atol = 1e-10;
  const Oscillator sys;
  auto s = make_stepper(o, 2);
  s->reset(sys, 0.0, Vec::Unit(2, 0));
  const IntegrateResult r = integrate(sys, *s, 10.0, {}, o);
  REQUIRE(r.reason == StopReason::kReachedEnd);
  CHECK(r.t == 10.0);
  CHECK(std::abs(s->y()[0] - std::cos(10.0)) < 1e-8);
  CHECK(std::abs(s->y()[1] + std::sin(10.0)) < 1e-8);
  // Loose tolerances: fewer steps, still sensible.
  SolverOptions loose = o;
  loose.rtol = loose.atol = 1e-6;
  auto s2 = make_stepper(loose, 2);
  s2->reset(sys, 0.0, Vec::Unit(2, 0));
  REQUIRE(integrate(sys, *s2, 10.0, {}, loose).reason == StopReason::kReachedEnd);
  CHECK(s2->counters().steps_accepted < s->counters().steps_accepted);
  CHECK(std::abs(s2->y()[0] - std::cos(10.0)) < 1e-4);

  // A step shortened to hit t_end keeps the adapted size for the next step.
  const double h_adapted = s->h();
  REQUIRE(integrate(sys, *s, s->t() + 1e-7, {}, o).reason == StopReason::kReachedEnd);
  CHECK(s->h() >= h_adapted);
}

TEST_CASE("ode: event location on a ballistic arc", "[ode]") {
  const Method m = GENERATE(Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5);
  INFO("method " << to_string(m));
  SolverOptions o;
  o.method = m;
  o.h_fixed = 1e-3;
  o.rtol = o.atol = 1e-9;
  const double z0 = 1.0, v0 = 2.0, level = 0.3;
  const double t_star = (v0 + std::sqrt(v0 * v0 + 2.0 * kGravity * (z0 - level))) / kGravity;
  const double t_apex = v0 / kGravity;
  // Euler's own trajectory is only first-order accurate; the others are exact
  // on a quadratic.
  const double t_tol = m == Method::kEuler ? 1e-2 : 1e-9;
  const Ballistic sys;
  const HeightEvent touchdown(level);
  const ApexEvent apex;
  const EventFunction* events[] = {&touchdown, &apex};
  auto s = make_stepper(o, 2);
  s->reset(sys, 0.0, (Vec(2) << z0, v0).finished());

  // The apex comes first although it is listed second.
  IntegrateResult r = integrate(sys, *s, 5.0, events, o);
  REQUIRE(r.reason == StopReason::kEvent);
  CHECK(r.event_index == 1);
  CHECK(std::abs(r.t - t_apex) < t_tol);
  CHECK(std::abs(s->y()[1]) <= 1e-9);
  CHECK(s->t() == r.t);

  // Continue (the apex now sits at v <= 0, so it must not retrigger).
  class LastStop final : public StepObserver {
   public:
    void on_step(const Stepper& st, double t_stop) override {
      CHECK(t_stop <= st.t());
      CHECK(t_stop > st.t_prev());
      last = t_stop;
    }
    double last = 0.0;
  } obs;
  r = integrate(sys, *s, 5.0, events, o, &obs);
  REQUIRE(r.reason == StopReason::kEvent);
  CHECK(r.event_index == 0);
  CHECK(std::abs(r.t - t_star) < t_tol);
  CHECK(std::abs(s->y()[0] - level) <= 1e-9);
  CHECK(s->y()[0] <= level);  // reported on the post-crossing side
  CHECK(obs.last == r.t);
  CHECK(s->counters().events == 2);
}

TEST_CASE("ode: no event at the start point", "[ode]") {
  const Method m = GENERATE(Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5);
  INFO("method " << to_string(m));
  SolverOptions o;
  o.method = m;
  const Ballistic sys;
  const HeightEvent ground(0.0);
  const EventFunction* events[] = {&ground};
  auto s = make_stepper(o, 2);
  s->reset(sys, 0.0, (Vec(2) << 0.0, -1.0).finished());  // on g = 0, moving down
  const IntegrateResult r = integrate(sys, *s, 0.5, events, o);
  CHECK(r.reason == StopReason::kReachedEnd);
  CHECK(s->counters().events == 0);
}

TEST_CASE("ode: restart after bounces matches the analytic bouncing ball", "[ode]") {
  const Method m = GENERATE(Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5);
  INFO("method " << to_string(m));
  SolverOptions o;
  o.method = m;
  o.h_fixed = m == Method::kEuler ? 1e-5 : 1e-3;
  o.rtol = o.atol = 1e-10;
  const double z0 = 1.0, e = 0.8;  // drop height [m], restitution [-]
  const int bounces = 4;
  // Analytic: first impact at t1 with speed u0, then flights of 2 u_k / g.
  double t_bounce = std::sqrt(2.0 * z0 / kGravity);
  double u = kGravity * t_bounce;
  for (int k = 1; k < bounces; ++k) {
    u *= e;
    t_bounce += 2.0 * u / kGravity;
  }
  u *= e;  // take-off speed after the last bounce [m/s]
  const double tau = 0.3 * 2.0 * u / kGravity;
  const double t_end = t_bounce + tau;
  const double z_ref = u * tau - 0.5 * kGravity * tau * tau;
  const double v_ref = u - kGravity * tau;

  const Ballistic sys;
  const HeightEvent ground(0.0);
  const EventFunction* events[] = {&ground};
  auto s = make_stepper(o, 2);
  s->reset(sys, 0.0, (Vec(2) << z0, 0.0).finished());
  long resets = 1, prev_steps = 0;
  int n_events = 0;
  for (;;) {
    const IntegrateResult r = integrate(sys, *s, t_end, events, o);
    CHECK(s->counters().steps_accepted > prev_steps);
    prev_steps = s->counters().steps_accepted;
    if (r.reason != StopReason::kEvent) {
      CHECK(r.reason == StopReason::kReachedEnd);
      break;
    }
    ++n_events;
    ++resets;
    Vec y = s->y();
    y[1] = -e * y[1];
    const double h_before = s->h();
    s->reset(sys, s->t(), y);
    ++resets;
    CHECK(s->h() == h_before);
    REQUIRE(n_events <= bounces);
  }
  CHECK(n_events == bounces);
  CHECK(s->counters().events == bounces);
  const double tol = m == Method::kEuler ? 1e-2 : 1e-8;
  CHECK(s->t() == t_end);
  CHECK(std::abs(s->y()[0] - z_ref) < tol);
  CHECK(std::abs(s->y()[1] - v_ref) < tol);
  // Every f call is counted: one per reset, the stages of every attempt and
  // DOPRI5's initial-step probe.
  const auto& c = s->counters();
  const long probe = m == Method::kDopri5 ? 1 : 0;
  CHECK(c.rhs_evaluations == resets + probe + stages(m) * (c.steps_accepted + c.steps_rejected));
}

TEST_CASE("ode: finite-time blow-up stops with a failure, not NaN", "[ode]") {
  const Method m = GENERATE(Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5);
  INFO("method " << to_string(m));
  SolverOptions o;
  o.method = m;
  const BlowUp sys;
  auto s = make_stepper(o, 1);
  s->reset(sys, 0.0, Vec::Ones(1));
  const IntegrateResult r = integrate(sys, *s, 2.0, {}, o);
  if (m == Method::kDopri5) {
    CHECK((r.reason == StopReason::kStepSizeCollapse || r.reason == StopReason::kNonFinite));
  } else {
    CHECK(r.reason == StopReason::kNonFinite);
  }
  CHECK(s->y().allFinite());
  CHECK(r.t < 1.1);
  CHECK(r.t == s->t());
}

TEST_CASE("ode: max_steps bounds the stepper's steps across integrate() calls and resets",
          "[ode]") {
  const Method m = GENERATE(Method::kEuler, Method::kDopri5);
  SolverOptions o;
  o.method = m;
  o.max_steps = 10;
  o.h_max = 1e-3;
  const Oscillator sys;
  auto s = make_stepper(o, 2);
  s->reset(sys, 0.0, Vec::Unit(2, 0));
  const IntegrateResult r = integrate(sys, *s, 1.0, {}, o);
  CHECK(r.reason == StopReason::kMaxSteps);
  CHECK(s->counters().steps_accepted + s->counters().steps_rejected == 10);
  // A restart (as the hybrid simulators do at every event) does not renew the budget.
  s->reset(sys, s->t(), s->y());
  const IntegrateResult again = integrate(sys, *s, 1.0, {}, o);
  CHECK(again.reason == StopReason::kMaxSteps);
  CHECK(again.attempts == 0);
  CHECK(s->counters().steps_accepted + s->counters().steps_rejected == 10);
}

// The crawl guard. Reference: dy/dt = -sign(y) from y = 1 reaches y = 0 at t = 1 and then
// slides along y = 0 (Filippov); an adaptive method must cross the discontinuity in every
// step, so its steps shrink to the tolerance and it crawls (~1e9 steps per second).
TEST_CASE("ode: the crawl guard ends an adaptive run that crawls at a discontinuity", "[ode]") {
  class Relay final : public OdeSystem {
   public:
    int dimension() const override { return 1; }
    void rhs(double, const Vec& y, Vec& d) const override { d[0] = y[0] > 0.0 ? -1.0 : 1.0; }
  } relay;
  const Method m = GENERATE(Method::kDopri5, Method::kRodas4);
  SolverOptions o;
  o.method = m;
  o.rtol = o.atol = 1e-9;
  auto s = make_stepper(o, 1);
  s->reset(relay, 0.0, Vec::Ones(1));
  const IntegrateResult r = integrate(relay, *s, 2.0, {}, o);
  INFO(to_string(m) << ": t " << r.t << ", attempts " << r.attempts);
  CHECK(r.reason == StopReason::kCrawling);
  CHECK(r.t > 1.0 - 1e-6);  // the smooth part is integrated normally
  CHECK(r.t < 1.1);
  const double budget = SolverOptions::kStepBudgetFloor + o.max_steps_per_second * r.t;
  CHECK(static_cast<double>(r.attempts) > budget);
  CHECK(static_cast<double>(r.attempts) <= budget + 1.0);  // stops at the first attempt over
  CHECK(r.attempts == s->counters().steps_accepted + s->counters().steps_rejected);
  CHECK(std::abs(s->y()[0]) < 1e-6);
  const std::string why = o.crawl_reason(r.attempts, r.t, r.t);
  CHECK(why.find(std::to_string(r.attempts)) != std::string::npos);

  // Off (0): only max_steps ends it.
  o.max_steps_per_second = 0.0;
  o.max_steps = 200000;
  auto s2 = make_stepper(o, 1);
  s2->reset(relay, 0.0, Vec::Ones(1));
  CHECK(integrate(relay, *s2, 2.0, {}, o).reason == StopReason::kMaxSteps);
  // Fixed-step methods are never "crawling": their step is the user's.
  o.method = Method::kEuler;
  o.max_steps_per_second = 1.0;
  CHECK_FALSE(o.crawling(10 * SolverOptions::kStepBudgetFloor, 1.0));
  o.max_steps_per_second = -1.0;
  std::string err;
  CHECK_FALSE(o.validate(&err));
  CHECK(err.find("max_steps_per_second") != std::string::npos);
  o.max_steps_per_second = 1.0;
  o.verlet_energy_budget = -1.0;
  CHECK_FALSE(o.validate(&err));
  CHECK(err.find("verlet_energy_budget") != std::string::npos);
}

TEST_CASE("ode: a non-finite event value stops the integration", "[ode]") {
  class NanEvent final : public EventFunction {
   public:
    double value(double t, const Vec&) const override {
      return t > 0.05 ? std::numeric_limits<double>::quiet_NaN() : 1.0;
    }
  } nan_event;
  const EventFunction* events[] = {&nan_event};
  SolverOptions o;
  o.method = Method::kRk4;
  const Oscillator sys;
  auto s = make_stepper(o, 2);
  s->reset(sys, 0.0, Vec::Unit(2, 0));
  const IntegrateResult r = integrate(sys, *s, 1.0, events, o);
  CHECK(r.reason == StopReason::kNonFinite);
  CHECK(r.event_index == 0);
  CHECK(r.t < 0.06);
}
