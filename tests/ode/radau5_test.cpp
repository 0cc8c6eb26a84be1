// RADAU5: convergence order and dense output order against the exact solution
// of a linear stiff system, L-stability, sparse/dense LU agreement, the
// finite-difference Jacobian fallback, and the case it exists for: a stiff
// spring that rotates (exact solution: uniform rotation on the relative
// equilibrium), where it must keep the angular velocity with steps far longer
// than the spring's vibration period.
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
#include "tests/ode/linear_stiff.hpp"
#include "tests/pseudorigid/scenes.hpp"

using pronk::ode::Method;
using pronk::ode::Vec;
using pronk::ode::test_systems::LinearStiff;

namespace {

/// Integrates with a constant step h: the tolerances are so loose that every
/// step is accepted (the problem is linear, so one Newton iteration is exact).
double fixed_step_error(const LinearStiff& sys, double h, double t_end, double* dense_err) {
  pronk::ode::SolverOptions o;
  o.method = Method::kRadau5;
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
    const double tm = s->t_prev() + 0.3 * (s->t() - s->t_prev());
    s->dense(tm, yd);
    if (tm > 0.3) worst_dense = std::max(worst_dense, (yd - sys.exact(tm, y0)).norm());
  }
  *dense_err = worst_dense;
  return (s->y() - sys.exact(t_end, y0)).norm();
}

/// Two 1 kg point masses in the plane joined by a spring (stiffness k [N/m],
/// rest length 1 m). State (x1, y1, x2, y2, p1x, p1y, p2x, p2y).
class Rotor final : public pronk::ode::OdeSystem {
 public:
  explicit Rotor(double k) : k_(k) {}
  int dimension() const override { return 8; }
  bool autonomous() const override { return true; }
  void rhs(double, const Vec& y, Vec& f) const override {
    const Eigen::Vector2d d = y.segment<2>(2) - y.segment<2>(0);
    const double l = d.norm();
    const Eigen::Vector2d force = -k_ * (l - 1.0) * d / l;  // on mass 2
    f.segment<2>(0) = y.segment<2>(4);
    f.segment<2>(2) = y.segment<2>(6);
    f.segment<2>(4) = -force;
    f.segment<2>(6) = force;
  }
  bool has_jacobian() const override { return true; }
  void jacobian(double, const Vec& y, Eigen::SparseMatrix<double>& j) const override {
    const Eigen::Vector2d d = y.segment<2>(2) - y.segment<2>(0);
    const double l = d.norm();
    const Eigen::Vector2d u = d / l;
    // d(force on 2)/d(d) = -k [u u^T + (1 - 1/l)(I - u u^T)]
    const Eigen::Matrix2d kd =
        -k_ *
        (u * u.transpose() + (1.0 - 1.0 / l) * (Eigen::Matrix2d::Identity() - u * u.transpose()));
    Eigen::MatrixXd jd = Eigen::MatrixXd::Zero(8, 8);
    jd.block<4, 4>(0, 4).setIdentity();
    jd.block<2, 2>(4, 0) = kd;
    jd.block<2, 2>(4, 2) = -kd;
    jd.block<2, 2>(6, 0) = -kd;
    jd.block<2, 2>(6, 2) = kd;
    j = jd.sparseView();
  }
  /// Relative equilibrium spinning at omega [rad/s]: k (l - 1) = omega^2 l / 2.
  double length(double omega) const { return k_ / (k_ - 0.5 * omega * omega); }
  /// Exact state at t of the relative equilibrium through (+-l/2, 0) at t = 0.
  Vec exact(double omega, double t) const {
    const double r = 0.5 * length(omega);
    const double c = std::cos(omega * t), s = std::sin(omega * t);
    Vec y(8);
    y << -r * c, -r * s, r * c, r * s, r * omega * s, -r * omega * c, -r * omega * s, r * omega * c;
    return y;
  }

 private:
  double k_;
};

struct RotorRun {
  double error = 0.0;  ///< max-norm state error at t_end relative to the momentum scale
  long steps = 0;
};

RotorRun run_rotor(Method m, double k, double tol) {
  const Rotor sys(k);
  const double omega = 2.0, t_end = 20.0;
  pronk::ode::SolverOptions o;
  o.method = m;
  o.rtol = o.atol = tol;
  auto s = pronk::ode::make_stepper(o, 8);
  s->reset(sys, 0.0, sys.exact(omega, 0.0));
  const auto r = pronk::ode::integrate(sys, *s, t_end, {}, o);
  REQUIRE(r.reason == pronk::ode::StopReason::kReachedEnd);
  RotorRun out;
  out.error = (s->y() - sys.exact(omega, t_end)).lpNorm<Eigen::Infinity>();
  out.steps = s->counters().steps_accepted + s->counters().steps_rejected;
  return out;
}

}  // namespace

TEST_CASE("radau5 converges with order 5 and dense output order 3 on a stiff linear system",
          "[ode][radau5]") {
  const LinearStiff sys(1e4, true);
  std::vector<double> err, dense;
  for (double h : {0.2, 0.1, 0.05, 0.025}) {
    double d = 0.0;
    err.push_back(fixed_step_error(sys, h, 2.0, &d));
    dense.push_back(d);
  }
  for (size_t i = 1; i < err.size(); ++i) {
    const double p = std::log2(err[i - 1] / err[i]);
    INFO("step order " << p << " errors " << err[i - 1] << " " << err[i]);
    CHECK(p > 4.5);
    CHECK(p < 5.8);
    const double pd = std::log2(dense[i - 1] / dense[i]);
    INFO("dense order " << pd << " errors " << dense[i - 1] << " " << dense[i]);
    CHECK(pd > 2.6);
  }
}

TEST_CASE("radau5 is L-stable: one huge step damps the stiff mode", "[ode][radau5]") {
  const LinearStiff sys(1e12, true);
  double d = 0.0;
  CHECK(fixed_step_error(sys, 0.1, 1.0, &d) < 1e-4);
}

TEST_CASE("radau5 adaptive: accurate, dense and sparse LU agree, finite-difference Jacobian",
          "[ode][radau5]") {
  const Vec y0 = Vec::Ones(4);
  auto run = [&](const LinearStiff& sys, int dense_max, long* jacobians) {
    pronk::ode::SolverOptions o;
    o.method = Method::kRadau5;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    o.dense_lu_max_dimension = dense_max;
    auto s = pronk::ode::make_stepper(o, 4);
    s->reset(sys, 0.0, y0);
    REQUIRE(pronk::ode::integrate(sys, *s, 5.0, {}, o).reason ==
            pronk::ode::StopReason::kReachedEnd);
    *jacobians = s->counters().jacobian_evaluations;
    return Vec(s->y());
  };
  const LinearStiff stiff(1e5, true);
  long jac = 0, jac2 = 0;
  const Vec yd = run(stiff, 100, &jac);
  const Vec ys = run(stiff, 0, &jac2);
  CHECK((yd - stiff.exact(5.0, y0)).norm() < 1e-7);
  CHECK((ys - yd).norm() < 1e-10);
  // A linear system converges at once: the Jacobian is reused across steps.
  long steps = 0;
  {
    pronk::ode::SolverOptions o;
    o.method = Method::kRadau5;
    o.rtol = 1e-8;
    o.atol = 1e-10;
    auto s = pronk::ode::make_stepper(o, 4);
    s->reset(stiff, 0.0, y0);
    REQUIRE(pronk::ode::integrate(stiff, *s, 5.0, {}, o).reason ==
            pronk::ode::StopReason::kReachedEnd);
    steps = s->counters().steps_accepted;
  }
  INFO(jac << " Jacobians for " << steps << " steps");
  CHECK(jac < steps / 2);
  const LinearStiff fd(1e3, false);
  const Vec yf = run(fd, 100, &jac);
  CHECK((yf - fd.exact(5.0, y0)).norm() < 1e-7);
}

TEST_CASE("radau5 keeps a rotating stiff spring on its relative equilibrium", "[ode][radau5]") {
  // k = 1e4 N/m on 1 kg: vibration period 63 ms, rotation period 3.1 s. The
  // Rosenbrock method linearises the spring once per step and loses accuracy
  // to the turning spring direction; the fully implicit method solves the
  // nonlinear stage equations (measured: 2.7e-7 in ~1000 steps vs 5.6e-6).
  const RotorRun radau = run_rotor(Method::kRadau5, 1e4, 1e-8);
  const RotorRun rodas = run_rotor(Method::kRodas4, 1e4, 1e-8);
  INFO("radau5: error " << radau.error << " in " << radau.steps << " steps; rodas4: " << rodas.error
                        << " in " << rodas.steps << " steps");
  CHECK(radau.error < 1e-6);
  CHECK(radau.error < 0.2 * rodas.error);
  CHECK(radau.steps < 2000);
}

TEST_CASE("radau5 with stage Jacobians steps over a stiff spinning satellite",
          "[ode][radau5][pseudorigid]") {
  // The satellite at k = 1e8 N/m (internal vibration ~2e4 rad/s, spin 1 rad/s), 20 s. With one
  // Jacobian shared by the stages the Newton iteration fails once h^2 Omega omega_stiff is not
  // small (measured: 8463 steps, 11152 rejected); with a Jacobian per stage once it fails it
  // steps at the rigid motion's pace (measured: 807 steps, omega error 1.6e-8).
  namespace pr = pronk::pseudorigid;
  namespace ts = pronk::pseudorigid::test_scenes;
  auto run = [](bool stages) {
    pr::Mechanism m = ts::satellite(1e8, 20.0);
    m.simulation.solver.method = Method::kRadau5;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-8;
    m.simulation.solver.radau5_stage_jacobians = stages;
    const pr::RunSummary r = pr::simulate(m);
    REQUIRE(r.status == pr::RunStatus::kCompleted);
    const pr::MechanismSystem sys(m);
    const double err = (sys.body_omega(0, r.y.back()) - ts::satellite_omega(r.t.back())).norm() /
                       ts::satellite_omega(0.0).norm();
    return std::make_pair(err, r.counters);
  };
  const auto [err, c] = run(true);
  const auto [err_shared, c_shared] = run(false);
  INFO("stage Jacobians: omega error " << err << ", " << c.steps_accepted << " steps, "
                                       << c.steps_rejected << " rejected; shared: " << err_shared
                                       << ", " << c_shared.steps_accepted << " steps, "
                                       << c_shared.steps_rejected << " rejected");
  CHECK(err < 1e-6);
  CHECK(err_shared < 1e-4);
  CHECK(c.steps_accepted < 1500);
  CHECK(c.steps_accepted + c.steps_rejected <
        0.2 * (c_shared.steps_accepted + c_shared.steps_rejected));
}

TEST_CASE("radau5 stage Jacobians leave a soft satellite to the shared Jacobian", "[ode][radau5]") {
  // At k = 1e4 N/m the shared-Jacobian Newton converges: the stage mode never starts and the
  // run is the same with or without it.
  namespace pr = pronk::pseudorigid;
  auto run = [](bool stages) {
    pr::Mechanism m = pronk::pseudorigid::test_scenes::satellite(1e4, 5.0);
    m.simulation.solver.method = Method::kRadau5;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-8;
    m.simulation.solver.radau5_stage_jacobians = stages;
    return pr::simulate(m);
  };
  const pr::RunSummary with = run(true), without = run(false);
  REQUIRE(with.status == pr::RunStatus::kCompleted);
  CHECK(with.y.back() == without.y.back());
  CHECK(with.counters.jacobian_evaluations == without.counters.jacobian_evaluations);
}
