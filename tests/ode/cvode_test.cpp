// Method cvode_bdf (SUNDIALS CVODE BDF behind pronk's Stepper): accuracy against exact
// solutions, its dense output, event location and restarts through integrate(), a
// pseudo-rigid mechanism against the analytic satellite precession, KLU against dense LU
// (the satellite, and the quad hopper drop whose contacts grow the Jacobian's pattern), and
// the CSC copy on a growing pattern.
#include <cmath>
#include <vector>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "app/bench/suite.hpp"
#include "io/load/mechanism_loader.hpp"
#include "sim/ode/solver.hpp"
#include "sim/ode/sundials_jacobian.hpp"
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

TEST_CASE("cvode_bdf: KLU and dense LU agree on the satellite", "[ode][cvode][pseudorigid]") {
  namespace pr = pronk::pseudorigid;
  namespace ts = pronk::pseudorigid::test_scenes;
  auto run = [](pronk::ode::CvodeLinearSolver ls) {
    pr::Mechanism m = ts::satellite(1e6, 5.0);
    m.simulation.solver.method = Method::kCvodeBdf;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-8;
    m.simulation.solver.cvode_linear_solver = ls;
    return std::make_pair(m, pr::simulate(m));
  };
  const auto [m, dense] = run(pronk::ode::CvodeLinearSolver::kDense);
  const auto [m2, klu] = run(pronk::ode::CvodeLinearSolver::kKlu);
  const auto [m3, automatic] = run(pronk::ode::CvodeLinearSolver::kAuto);
  REQUIRE(dense.status == pr::RunStatus::kCompleted);
  REQUIRE(klu.status == pr::RunStatus::kCompleted);
  const pr::MechanismSystem sys(m);
  auto omega_error = [&](const pr::RunSummary& r) {
    return (sys.body_omega(0, r.y.back()) - ts::satellite_omega(r.t.back())).norm() /
           ts::satellite_omega(0.0).norm();
  };
  const double diff = (sys.body_omega(0, klu.y.back()) - sys.body_omega(0, dense.y.back())).norm() /
                      ts::satellite_omega(0.0).norm();
  INFO("omega error: dense " << omega_error(dense) << " (" << dense.counters.steps_accepted
                             << " steps), klu " << omega_error(klu) << " ("
                             << klu.counters.steps_accepted << " steps); difference " << diff);
  CHECK(omega_error(dense) < 1e-5);
  CHECK(omega_error(klu) < 1e-5);
  CHECK(diff < 1e-5);  // both within CVODE's error of the same solution
  // Same Newton iteration, different round-off: similar work.
  CHECK(std::abs(klu.counters.steps_accepted - dense.counters.steps_accepted) <
        0.1 * dense.counters.steps_accepted);
  CHECK(klu.energy_drift <= 2e-6 * klu.energy_scale);
  // auto is KLU for a system with an analytic Jacobian: bit-identical to it.
  CHECK(automatic.y.back() == klu.y.back());
}

TEST_CASE("cvode_bdf: KLU follows contacts that grow the Jacobian's pattern",
          "[ode][cvode][pseudorigid]") {
  namespace pr = pronk::pseudorigid;
  // The bench's quad hopper drop (four feet on a frictional ground), 1 s: each touchdown adds
  // the contact's entries to the Jacobian; KLU must analyse the grown pattern again.
  const nlohmann::json doc = pronk::app::bench::quad_hopper_mechanism(1.0);
  const pr::Mechanism base = pronk::io::parse_mechanism(doc, "<quad>").mechanism;
  auto run = [&](pronk::ode::CvodeLinearSolver ls) {
    pr::Mechanism m = base;
    m.simulation.solver.method = Method::kCvodeBdf;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-7;
    m.simulation.solver.cvode_linear_solver = ls;
    return pr::simulate(m);
  };
  const pr::RunSummary dense = run(pronk::ode::CvodeLinearSolver::kDense);
  const pr::RunSummary klu = run(pronk::ode::CvodeLinearSolver::kKlu);
  REQUIRE(dense.status == pr::RunStatus::kCompleted);
  REQUIRE(klu.status == pr::RunStatus::kCompleted);
  const pr::MechanismSystem sys(base);
  double worst = 0.0;
  REQUIRE(klu.y.size() == dense.y.size());
  for (size_t i = 0; i < klu.y.size(); ++i) {
    worst = std::max(worst,
                     std::abs(sys.frames(klu.y[i])[0].com.z() - sys.frames(dense.y[i])[0].com.z()));
  }
  INFO("body height difference " << worst << " m; energy balance: dense "
                                 << dense.energy_drift / dense.energy_scale << ", klu "
                                 << klu.energy_drift / klu.energy_scale << "; steps "
                                 << dense.counters.steps_accepted << " / "
                                 << klu.counters.steps_accepted);
  CHECK(worst < 1e-4);  // of a 0.15 m drop
  CHECK(klu.energy_drift < 1e-3 * klu.energy_scale);
  CHECK(klu.energy_drift < 3.0 * dense.energy_drift + 1e-6 * klu.energy_scale);
}

TEST_CASE("sundials::SparsePattern: CSC copies on a pattern that only grows", "[ode][cvode]") {
  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  SUNMatrix a = SUNSparseMatrix(3, 3, 3, CSC_MAT, ctx);
  SUNMatrix d = SUNDenseMatrix(3, 3, ctx);
  pronk::ode::sundials::SparsePattern pattern;
  using Copy = pronk::ode::sundials::SparsePattern::Copy;
  auto dense_of = [](SUNMatrix s) {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (sunindextype c = 0; c < 3; ++c) {
      for (sunindextype k = SM_INDEXPTRS_S(s)[c]; k < SM_INDEXPTRS_S(s)[c + 1]; ++k) {
        m(SM_INDEXVALS_S(s)[k], c) += SM_DATA_S(s)[k];
      }
    }
    return m;
  };
  Eigen::Matrix3d j1;
  j1 << 0, 2, 0, 0, 0, 0, 3, 0, 0;  // no diagonal
  Eigen::SparseMatrix<double> s1 = j1.sparseView();
  CHECK(pattern.copy(s1, a) == Copy::kGrown);
  CHECK(pattern.nonzeros() == 5);  // the diagonal is stored
  CHECK(dense_of(a) == j1);
  Eigen::Matrix3d j2 = 0.5 * j1;
  j2(0, 1) = 0.0;  // an entry that vanishes: explicitly zero on the pattern
  CHECK(pattern.copy(j2.sparseView(), a) == Copy::kSame);
  CHECK(dense_of(a) == j2);
  Eigen::Matrix3d j3 = j1;
  j3(1, 2) = -4.0;  // a new entry: the pattern grows, keeping the old ones
  CHECK(pattern.copy(j3.sparseView(), a) == Copy::kGrown);
  CHECK(pattern.nonzeros() == 6);
  CHECK(dense_of(a) == j3);
  CHECK(pattern.copy(s1, a) == Copy::kSame);
  CHECK(dense_of(a) == j1);
  Eigen::Matrix3d bad = j1;
  bad(2, 0) = std::nan("");
  CHECK(pattern.copy(bad.sparseView(), a) == Copy::kNonFinite);
  CHECK(pronk::ode::sundials::copy_dense(s1, d));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) CHECK(SM_ELEMENT_D(d, r, c) == j1(r, c));
  }
  SUNMatDestroy(a);
  SUNMatDestroy(d);
  SUNContext_Free(&ctx);
}
