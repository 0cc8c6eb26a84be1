// RODAS4: convergence order, dense output order, stiff efficiency, sparse/dense
// LU agreement and the finite-difference Jacobian fallback, against the exact
// solution of a linear stiff system.
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "sim/ode/solver.hpp"
#include "tests/ode/linear_stiff.hpp"

using pronk::ode::Method;
using pronk::ode::Vec;
using pronk::ode::test_systems::LinearStiff;

namespace {

/// Integrates with a constant step h (tolerances so loose every step is accepted).
double fixed_step_error(const LinearStiff& sys, double h, double t_end, double* dense_err) {
  pronk::ode::SolverOptions o;
  o.method = Method::kRodas4;
  o.rtol = o.atol = 1e30;
  o.h_initial = h;
  o.h_max = h;
  auto s = pronk::ode::make_stepper(o, 4);
  const Vec y0 = Vec::Ones(4);
  s->reset(sys, 0.0, y0);
  double worst_dense = 0.0;
  Vec yd(4);
  while (s->t() < t_end - 1e-12) {
    REQUIRE(s->step(sys, t_end) == pronk::ode::StepStatus::kOk);
    const double tm = 0.5 * (s->t_prev() + s->t());
    s->dense(tm, yd);
    // The stiff transient (time constant 1/lambda) is not resolved by design.
    if (tm > 0.3) worst_dense = std::max(worst_dense, (yd - sys.exact(tm, y0)).norm());
  }
  *dense_err = worst_dense;
  return (s->y() - sys.exact(t_end, y0)).norm();
}

}  // namespace

TEST_CASE("rodas4 converges with order 4 and dense output order 3 on a stiff linear system",
          "[ode][rosenbrock]") {
  const LinearStiff sys(1e4, true);
  std::vector<double> err, dense;
  for (double h : {0.1, 0.05, 0.025, 0.0125}) {
    double d = 0.0;
    err.push_back(fixed_step_error(sys, h, 2.0, &d));
    dense.push_back(d);
  }
  for (size_t i = 1; i < err.size(); ++i) {
    const double p = std::log2(err[i - 1] / err[i]);
    INFO("step order " << p << " errors " << err[i - 1] << " " << err[i]);
    CHECK(p > 3.6);
    CHECK(p < 4.7);
    const double pd = std::log2(dense[i - 1] / dense[i]);
    INFO("dense order " << pd);
    CHECK(pd > 2.6);
  }
}

TEST_CASE("rodas4 is L-stable: one huge step damps the stiff mode", "[ode][rosenbrock]") {
  const LinearStiff sys(1e12, true);
  double d = 0.0;
  // h * lambda = 1e11: an explicit method would explode, RODAS4 stays bounded.
  const double e = fixed_step_error(sys, 0.1, 1.0, &d);
  CHECK(e < 1e-2);
}

TEST_CASE(
    "rodas4 adaptive: accurate, far cheaper than dopri5 when stiff, dense and sparse LU agree",
    "[ode][rosenbrock]") {
  const LinearStiff sys(1e5, true);
  const Vec y0 = Vec::Ones(4);
  auto run = [&](Method m, int dense_max, long* steps, long* lu) {
    pronk::ode::SolverOptions o;
    o.method = m;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.dense_lu_max_dimension = dense_max;
    auto s = pronk::ode::make_stepper(o, 4);
    s->reset(sys, 0.0, y0);
    const auto r = pronk::ode::integrate(sys, *s, 5.0, {}, o);
    REQUIRE(r.reason == pronk::ode::StopReason::kReachedEnd);
    *steps = s->counters().steps_accepted + s->counters().steps_rejected;
    *lu = s->counters().lu_factorizations;
    return Vec(s->y());
  };
  long steps_r = 0, steps_d = 0, lu = 0, lu2 = 0;
  const Vec yr = run(Method::kRodas4, 100, &steps_r, &lu);
  const Vec ys = run(Method::kRodas4, 0, &steps_r, &lu2);
  const Vec yd = run(Method::kDopri5, 100, &steps_d, &lu2);
  const Vec ex = sys.exact(5.0, y0);
  CHECK((yr - ex).norm() < 1e-7);
  CHECK((ys - yr).norm() < 1e-12);
  CHECK((yd - ex).norm() < 1e-7);
  CHECK(lu >= steps_r / 2);
  INFO("rodas4 steps " << steps_r << ", dopri5 steps " << steps_d);
  CHECK(steps_d > 50 * steps_r);
}

TEST_CASE("rodas4 without an analytic Jacobian uses finite differences", "[ode][rosenbrock]") {
  const LinearStiff sys(1e3, false);
  pronk::ode::SolverOptions o;
  o.method = Method::kRodas4;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  auto s = pronk::ode::make_stepper(o, 4);
  const Vec y0 = Vec::Ones(4);
  s->reset(sys, 0.0, y0);
  REQUIRE(pronk::ode::integrate(sys, *s, 3.0, {}, o).reason == pronk::ode::StopReason::kReachedEnd);
  CHECK((s->y() - sys.exact(3.0, y0)).norm() < 1e-7);
  CHECK(s->counters().jacobian_evaluations >= s->counters().steps_accepted);
}
