// The event-aware integration driver far from t = 0 (docs/solvers.md): events located on
// the dense output to tolerance even where the spacing of doubles exceeds a
// fraction of event_tol (t > ~256 s at event_tol = 1e-13 s).
#include <cmath>

#include <catch2/catch.hpp>

#include "sim/ode/solver.hpp"

using namespace pronk;

namespace {

/// Ballistic height z'' = -g, reset to a fixed upward speed at every ground contact.
class Ballistic final : public ode::OdeSystem {
 public:
  int dimension() const override { return 2; }
  void rhs(double, const ode::Vec& y, ode::Vec& f) const override {
    f[0] = y[1];
    f[1] = -9.81;
  }
};

class Ground final : public ode::EventFunction {
 public:
  double value(double, const ode::Vec& y) const override { return y[0]; }
};

}  // namespace

TEST_CASE("extreme: events past t = 256 s are located to tolerance", "[extremes][ode]") {
  // Hops of exactly 2 v / g: every touchdown time is known in closed form.
  Ballistic sys;
  Ground ground;
  const ode::EventFunction* events[] = {&ground};
  const double v = 1.98, period = 2.0 * v / 9.81;
  for (const auto method : {ode::Method::kDopri5, ode::Method::kRk4}) {
    ode::SolverOptions o;
    o.method = method;
    o.h_fixed = 0.01;
    auto stepper = ode::make_stepper(o, 2);
    ode::Vec y(2);
    y << 0.0, v;
    const double t0 = 1000.0;  // start late: doubles are 1.1e-13 s apart here
    stepper->reset(sys, t0, y);
    double worst_time = 0.0, worst_height = 0.0;
    for (int hop = 1; hop <= 20; ++hop) {
      const auto r = ode::integrate(sys, *stepper, t0 + 1e3, events, o);
      REQUIRE(r.reason == ode::StopReason::kEvent);
      worst_time = std::max(worst_time, std::abs(r.t - (t0 + hop * period)));
      worst_height = std::max(worst_height, std::abs(stepper->y()[0]));
      y << 0.0, v;
      stepper->reset(sys, r.t, y);
    }
    INFO("method " << ode::to_string(method));
    CHECK(worst_time < 1e-10);
    CHECK(worst_height < 1e-9);
  }
}
