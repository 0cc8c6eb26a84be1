// Method cvode_bdf (SUNDIALS CVODE BDF behind pronk's Stepper): accuracy against exact
// solutions, its dense output, event location and restarts through integrate(), and a
// pseudo-rigid mechanism against the analytic satellite precession.
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
#include "tests/ode/linear_stiff.hpp"
#include "tests/pseudorigid/scenes.hpp"

namespace {

using pronk::ode::Method;
using pronk::ode::Vec;
using pronk::ode::test_systems::LinearStiff;

pronk::ode::SolverOptions cvode_options(double tol) {
  pronk::ode::SolverOptions o;
  o.method = Method::kCvodeBdf;
  o.rtol = tol;
  o.atol = tol;
  return o;
}

/// A ball falling in z (y = [z, v]) that bounces at z = 0 with restitution e: after a drop
/// from h the n-th impact is at t_n = t_1 (1 + 2 e (1 - e^(n-1)) / (1 - e)), t_1 = sqrt(2h/g).
class CvodeBall final : public pronk::ode::OdeSystem {
 public:
  int dimension() const override { return 2; }
  void rhs(double, const Vec& y, Vec& f) const override {
    f.resize(2);
    f << y[1], -9.81;
  }
};

class CvodeGround final : public pronk::ode::EventFunction {
 public:
  double value(double, const Vec& y) const override { return y[0]; }
  int direction() const override { return -1; }
};

}  // namespace

TEST_CASE("cvode_bdf: a stiff linear system to its tolerance, analytic and DQ Jacobians",
          "[ode][cvode]") {
  const Vec y0 = Vec::Ones(4);
  for (const bool analytic : {true, false}) {
    const LinearStiff sys(1e5, analytic);
    const pronk::ode::SolverOptions o = cvode_options(1e-9);
    auto s = pronk::ode::make_stepper(o, 4);
    s->reset(sys, 0.0, y0);
    REQUIRE(pronk::ode::integrate(sys, *s, 5.0, {}, o).reason ==
            pronk::ode::StopReason::kReachedEnd);
    const auto& c = s->counters();
    INFO((analytic ? "analytic" : "difference quotients")
         << ": error " << (s->y() - sys.exact(5.0, y0)).norm() << ", " << c.steps_accepted
         << " steps, " << c.jacobian_evaluations << " Jacobians, " << c.lu_factorizations << " LU");
    CHECK(s->t() == 5.0);
    CHECK((s->y() - sys.exact(5.0, y0)).norm() < 1e-6);
    // BDF reuses its Jacobian and its factorisation across steps on a linear system.
    CHECK(c.steps_accepted > 50);
    CHECK(c.lu_factorizations < c.steps_accepted / 2);
    if (analytic) CHECK(c.jacobian_evaluations < c.steps_accepted / 4);
    // Stiff: an explicit method would need ~1e5 x 5 / 2.8 steps; BDF takes far fewer.
    CHECK(c.steps_accepted < 5000);
  }
}

TEST_CASE("cvode_bdf: dense output inside every step follows the exact solution", "[ode][cvode]") {
  const LinearStiff sys(1e3, true);
  const Vec y0 = Vec::Ones(4);
  const pronk::ode::SolverOptions o = cvode_options(1e-10);
  auto s = pronk::ode::make_stepper(o, 4);
  s->reset(sys, 0.0, y0);
  double worst = 0.0;
  Vec y;
  int steps = 0;
  while (s->t() < 3.0) {
    REQUIRE(s->step(sys, 3.0) == pronk::ode::StepStatus::kOk);
    ++steps;
    for (double f : {0.25, 0.5, 0.75}) {
      const double t = s->t_prev() + f * (s->t() - s->t_prev());
      s->dense(t, y);
      worst = std::max(worst, (y - sys.exact(t, y0)).norm());
    }
    s->dense(s->t(), y);
    CHECK(y == s->y());
  }
  INFO(steps << " steps, worst dense error " << worst);
  CHECK(s->t() == 3.0);  // the stop time is met exactly
  CHECK(worst < 1e-7);
}

TEST_CASE("cvode_bdf: events located on its dense output, restarts keep the counters",
          "[ode][cvode]") {
  const CvodeBall ball;
  const CvodeGround ground;
  const pronk::ode::SolverOptions o = cvode_options(1e-10);
  auto s = pronk::ode::make_stepper(o, 2);
  const double h = 1.0, e = 0.8, g = 9.81;
  Vec y(2);
  y << h, 0.0;
  s->reset(ball, 0.0, y);
  const double t1 = std::sqrt(2.0 * h / g);
  long steps_before = 0;
  const std::vector<const pronk::ode::EventFunction*> events = {&ground};
  for (int n = 1; n <= 4; ++n) {
    const auto r = pronk::ode::integrate(ball, *s, 10.0, events, o);
    REQUIRE(r.reason == pronk::ode::StopReason::kEvent);
    const double expected = t1 * (1.0 + 2.0 * e * (1.0 - std::pow(e, n - 1)) / (1.0 - e));
    INFO("impact " << n << " at " << r.t << " (exact " << expected << ")");
    CHECK(std::abs(r.t - expected) < 1e-8);
    CHECK(std::abs(s->y()[0]) < 1e-8);
    CHECK(s->counters().steps_accepted > steps_before);  // accumulated across restarts
    steps_before = s->counters().steps_accepted;
    y = s->y();
    y[0] = 0.0;
    y[1] = -e * y[1];
    s->reset(ball, r.t, y);
  }
  CHECK(s->counters().events == 4);
}

TEST_CASE("cvode_bdf: the pseudo-rigid satellite follows the analytic precession",
          "[ode][cvode][pseudorigid]") {
  namespace pr = pronk::pseudorigid;
  pr::Mechanism m = pronk::pseudorigid::test_scenes::satellite(1e6, 5.0);
  m.simulation.solver.method = Method::kCvodeBdf;
  m.simulation.solver.rtol = m.simulation.solver.atol = 1e-8;
  const pr::RunSummary r = pr::simulate(m);
  REQUIRE(r.status == pr::RunStatus::kCompleted);
  const pr::MechanismSystem sys(m);
  namespace ts = pronk::pseudorigid::test_scenes;
  const double err = (sys.body_omega(0, r.y.back()) - ts::satellite_omega(r.t.back())).norm() /
                     ts::satellite_omega(0.0).norm();
  INFO("omega error " << err << ", " << r.counters.steps_accepted << " steps, "
                      << r.counters.jacobian_evaluations << " Jacobians");
  // k = 1e6 N/m: the model's own error (strain ~2e-6) bounds the omega error from below.
  CHECK(err < 1e-5);
  CHECK(r.counters.jacobian_evaluations > 0);  // the analytic Jacobian was used
  // The energy balance (Gauss quadrature of the dissipated power on the dense output, as for
  // rodas4): measured 1.0e-6 of the scale at this tolerance.
  CHECK(r.energy_drift <= 2e-6 * r.energy_scale);
}
