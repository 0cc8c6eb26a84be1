// Velocity Verlet (method "verlet") against closed-form references: second order,
// the exactly conserved modified energy of the harmonic oscillator (the signature of
// a symplectic method), exact angular momentum under a central force, the stability
// limit omega h = 2, second order with velocity-dependent forces, dense output, and
// a clear error for systems without positions and momenta. With a dissipation split:
// the exactly closing discrete energy balance E - T + D, the exact creep speed under a
// stiff damper, and stability at any damping.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "sim/ode/mechanical_system.hpp"
#include "sim/ode/solver.hpp"
#include "sim/ode/verlet.hpp"

namespace {

using pronk::ode::integrate;
using pronk::ode::make_stepper;
using pronk::ode::MechanicalSystem;
using pronk::ode::Method;
using pronk::ode::OdeSystem;
using pronk::ode::SolverOptions;
using pronk::ode::Vec;

/// Damped oscillator m x'' = -k x - c x' as (x [m], p [N s]).
class MassSpring final : public MechanicalSystem {
 public:
  MassSpring(double m, double k, double c) : m_(m), k_(k), c_(c) {}
  int dimension() const override { return 2; }
  void rhs(double, const Vec& y, Vec& dydt) const override {
    dydt[0] = y[1] / m_;
    dydt[1] = -k_ * y[0] - c_ * y[1] / m_;
  }
  void momentum_mask(Vec& mask) const override {
    mask.resize(2);
    mask << 0.0, 1.0;
  }
  void position_rate(const Vec& y, Vec& dydt) const override { dydt[0] = y[1] / m_; }

  /// Exact x(t) from x(0) = 1, p(0) = 0 (underdamped) [m].
  double exact(double t) const {
    const double zeta = c_ / (2.0 * std::sqrt(k_ * m_));
    const double w0 = std::sqrt(k_ / m_);
    const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
    return std::exp(-zeta * w0 * t) * (std::cos(wd * t) + zeta * w0 / wd * std::sin(wd * t));
  }

 private:
  double m_, k_, c_;  ///< [kg], [N/m], [N s/m]
};

/// A unit mass in the plane under the central force -r / |r|^3 (Kepler): (x, y, px, py).
class Kepler final : public MechanicalSystem {
 public:
  int dimension() const override { return 4; }
  void rhs(double, const Vec& y, Vec& dydt) const override {
    const double r3 = std::pow(y[0] * y[0] + y[1] * y[1], 1.5);
    dydt << y[2], y[3], -y[0] / r3, -y[1] / r3;
  }
  void momentum_mask(Vec& mask) const override {
    mask.resize(4);
    mask << 0.0, 0.0, 1.0, 1.0;
  }
  void position_rate(const Vec& y, Vec& dydt) const override { dydt.head<2>() = y.tail<2>(); }
};

/// m x'' = F - k x - c x' with the damper split off (MechanicalSystem::dissipate): backward Euler
/// of the damper over h, booked as the interface prescribes. (x [m], p [N s]).
class SplitSpring final : public MechanicalSystem {
 public:
  /// metric: offers MechanicalSystem::kinetic_energy (the stepper then books with the held force).
  SplitSpring(double m, double k, double c, double f, bool metric = false)
      : m_(m), k_(k), c_(c), f_(f), metric_(metric) {}
  int dimension() const override { return 2; }
  void rhs(double, const Vec& y, Vec& dydt) const override {
    dydt[0] = y[1] / m_;
    dydt[1] = f_ - k_ * y[0] - c_ * y[1] / m_;
  }
  void momentum_mask(Vec& mask) const override {
    mask.resize(2);
    mask << 0.0, 1.0;
  }
  void position_rate(const Vec& y, Vec& dydt) const override { dydt[0] = y[1] / m_; }
  bool has_dissipation_split() const override { return true; }
  void conservative_rhs(double, const Vec& y, Vec& dydt) const override {
    dydt[0] = y[1] / m_;
    dydt[1] = f_ - k_ * y[0];
  }
  double dissipate(double, double h, const Vec& y_ref, Vec& y) const override {
    const double p0 = y[1];
    y[1] = p0 / (1.0 + h * c_ / m_);
    const double dp = y[1] - p0;
    return -dp * (y_ref[1] + 0.5 * dp) / m_;
  }
  double kinetic_energy(const Vec& y) const override {
    return metric_ ? y[1] * y[1] / (2 * m_) : -1.0;
  }
  /// Verlet's term with the held force, reconstructed independently: the last half step's
  /// backward Euler damper leaves p, so its mean force was F_d = -c p / m; the share
  /// a in [0, 1] of F_d that cancels the spring-and-push force F counts [J].
  double held_term(const Vec& y, double h) const {
    const double f = f_ - k_ * y[0], fd = -c_ * y[1] / m_;
    const double a = fd != 0.0 ? std::clamp(-f / fd, 0.0, 1.0) : 0.0;
    return h * h * (f + a * fd) * (f + a * fd) / (8 * m_);
  }
  /// Energy with the potential of the constant force F [J].
  double energy(const Vec& y) const {
    return y[1] * y[1] / (2 * m_) + 0.5 * k_ * y[0] * y[0] - f_ * y[0];
  }
  /// Verlet's bounded term T = h^2 |F(x)|^2 / 8 m of the conservative force [J].
  double verlet_term(const Vec& y, double h) const {
    const double f = f_ - k_ * y[0];
    return h * h * f * f / (8 * m_);
  }

 private:
  double m_, k_, c_, f_;  ///< [kg], [N/m], [N s/m], [N]
  bool metric_;
};

/// Verlet's invariant E - T_net + D - offset [J] of stepper s on sys (exact for quadratic
/// potentials through step-size switches and restarts).
double verlet_invariant(const SplitSpring& sys, const pronk::ode::Stepper& s) {
  const pronk::ode::VerletInfo& v = *s.verlet_info();
  return sys.energy(s.y()) - v.verlet_term() + v.booked_dissipation() - v.switching_offset();
}

/// x' = -x: no positions and momenta.
class Decay final : public OdeSystem {
 public:
  int dimension() const override { return 1; }
  void rhs(double, const Vec& y, Vec& dydt) const override { dydt[0] = -y[0]; }
};

SolverOptions verlet(double h) {
  SolverOptions o;
  o.method = Method::kVerlet;
  o.h_fixed = h;
  return o;
}

/// |x(t_end) - exact| of the oscillator with step h.
double oscillator_error(const MassSpring& sys, double h, double t_end) {
  const SolverOptions o = verlet(h);
  auto s = make_stepper(o, 2);
  Vec y(2);
  y << 1.0, 0.0;
  s->reset(sys, 0.0, y);
  integrate(sys, *s, t_end, {}, o);
  return std::abs(s->y()[0] - sys.exact(t_end));
}

}  // namespace

TEST_CASE("verlet is second order, also with a velocity-dependent force", "[ode][verlet]") {
  for (double c : {0.0, 0.3}) {
    const MassSpring sys(2.0, 50.0, c);  // omega = 5 rad/s
    const double e1 = oscillator_error(sys, 0.01, 3.0);
    const double e2 = oscillator_error(sys, 0.005, 3.0);
    const double order = std::log2(e1 / e2);
    INFO("damping " << c << ": errors " << e1 << ", " << e2 << ", order " << order);
    CHECK(order > 1.9);
    CHECK(order < 2.1);
  }
}

TEST_CASE("verlet conserves the harmonic oscillator's modified energy exactly", "[ode][verlet]") {
  // Velocity Verlet maps (x, p) linearly with determinant 1 and conserves
  // H_h = p^2 / 2m + k x^2 / 2 (1 - (omega h / 2)^2) exactly; the true energy only
  // oscillates, by at most (omega h)^2 / (4 - (omega h)^2) of it, and never drifts.
  const double m = 0.5, k = 2e4, h = 2e-3;  // omega h = 0.4
  const double wh = std::sqrt(k / m) * h;
  const MassSpring sys(m, k, 0.0);
  const SolverOptions o = verlet(h);
  auto s = make_stepper(o, 2);
  Vec y(2);
  y << 0.01, 0.0;
  s->reset(sys, 0.0, y);
  auto modified = [&](const Vec& v) {
    return v[1] * v[1] / (2 * m) + 0.5 * k * v[0] * v[0] * (1 - wh * wh / 4);
  };
  auto energy = [&](const Vec& v) { return v[1] * v[1] / (2 * m) + 0.5 * k * v[0] * v[0]; };
  const double h0 = modified(y), e0 = energy(y);
  double worst_modified = 0.0, worst_energy = 0.0;
  for (int i = 0; i < 100000; ++i) {
    REQUIRE(s->step(sys, 1e9) == pronk::ode::StepStatus::kOk);
    worst_modified = std::max(worst_modified, std::abs(modified(s->y()) - h0) / h0);
    worst_energy = std::max(worst_energy, std::abs(energy(s->y()) - e0) / e0);
  }
  CHECK(worst_modified < 1e-11);
  CHECK(worst_energy <= wh * wh / (4 - wh * wh) * (1 + 1e-9));
  CHECK(worst_energy > 0.5 * wh * wh / (4 - wh * wh));  // the bound is attained, not loose
  CHECK(s->counters().rhs_evaluations == 100001);       // one RHS per step
}

TEST_CASE("verlet conserves angular momentum exactly under a central force", "[ode][verlet]") {
  const Kepler sys;
  const SolverOptions o = verlet(0.01);
  auto s = make_stepper(o, 4);
  Vec y(4);
  y << 1.0, 0.0, 0.0, 1.2;  // an ellipse with eccentricity 0.44
  s->reset(sys, 0.0, y);
  const double l0 = y[0] * y[3] - y[1] * y[2];
  const double e0 = 0.5 * y.tail<2>().squaredNorm() - 1.0 / y.head<2>().norm();
  double worst_l = 0.0, worst_e = 0.0;
  for (int i = 0; i < 20000; ++i) {  // ~ 30 orbits
    REQUIRE(s->step(sys, 1e9) == pronk::ode::StepStatus::kOk);
    const Vec& v = s->y();
    worst_l = std::max(worst_l, std::abs(v[0] * v[3] - v[1] * v[2] - l0));
    worst_e = std::max(worst_e,
                       std::abs(0.5 * v.tail<2>().squaredNorm() - 1.0 / v.head<2>().norm() - e0));
  }
  CHECK(worst_l < 1e-12);
  // Energy: bounded O(h^2) oscillation (no secular drift over 30 orbits).
  CHECK(worst_e < 1e-3 * std::abs(e0));
}

TEST_CASE("verlet is stable below omega h = 2 and grows without bound above", "[ode][verlet]") {
  const MassSpring sys(1.0, 1e6, 0.0);  // omega = 1000 rad/s
  for (const double wh : {1.95, 2.05}) {
    const SolverOptions o = verlet(wh / 1000.0);
    auto s = make_stepper(o, 2);
    Vec y(2);
    y << 1.0, 0.0;
    s->reset(sys, 0.0, y);
    double peak = 0.0;
    for (int i = 0; i < 2000; ++i) {
      s->step(sys, 1e9);
      peak = std::max(peak, std::abs(s->y()[0]));
    }
    INFO("omega h = " << wh << ": peak |x| " << peak);
    if (wh < 2.0) {
      // Bounded by the modified-energy ellipse: |x| <= 1 / sqrt(1 - (omega h / 2)^2).
      CHECK(peak <= 1.0 / std::sqrt(1.0 - wh * wh / 4.0) * (1 + 1e-9));
    } else {
      CHECK(peak > 1e10);
    }
  }
}

TEST_CASE("verlet dense output interpolates to third order inside a step", "[ode][verlet]") {
  const MassSpring sys(1.0, 1.0, 0.0);  // x = cos t
  const SolverOptions o = verlet(0.05);
  auto s = make_stepper(o, 2);
  Vec y(2);
  y << 1.0, 0.0;
  s->reset(sys, 0.0, y);
  for (int i = 0; i < 10; ++i) s->step(sys, 1e9);
  Vec ym;
  const double tm = 0.5 * (s->t_prev() + s->t());
  s->dense(tm, ym);
  // Step error O(h^3) of the method plus the Hermite error O(h^4).
  CHECK(std::abs(ym[0] - std::cos(tm)) < 1e-3);
  s->dense(s->t(), ym);
  CHECK(ym[0] == s->y()[0]);
}

TEST_CASE("verlet refuses a system without positions and momenta", "[ode][verlet]") {
  const Decay sys;
  auto s = make_stepper(verlet(0.1), 1);
  Vec y(1);
  y << 1.0;
  CHECK_THROWS_AS(s->reset(sys, 0.0, y), std::invalid_argument);
  CHECK(s->verlet_info() != nullptr);
  SolverOptions rk4 = verlet(0.1);
  rk4.method = Method::kRk4;
  CHECK(make_stepper(rk4, 1)->verlet_info() == nullptr);  // the bookkeeping is verlet's
  SolverOptions o = verlet(0.1);
  std::string err;
  CHECK(o.validate(&err));
  Method m;
  CHECK(pronk::ode::parse_method("verlet", &m));
  CHECK(m == Method::kVerlet);
  CHECK_FALSE(pronk::ode::is_adaptive(m));
}

TEST_CASE("verlet with a dissipation split closes the energy balance exactly", "[ode][verlet]") {
  // E - T + booked dissipation is an exact invariant of the split scheme for quadratic
  // potentials (T = h^2 |F|^2 / 8m): from light damping to a damper 50x stiffer than the
  // step (h c / m = 50) and a spring at omega h = 1.6, and with a constant force.
  for (const double c : {0.1, 10.0, 5e3}) {
    for (const double f : {0.0, 3.0}) {
      const double m = 0.2, k = 1280.0, h = 2e-3;  // omega h = 1.6
      const SplitSpring sys(m, k, c, f);
      auto s = make_stepper(verlet(h), 2);
      Vec y(2);
      y << 0.05, 0.4;
      s->reset(sys, 0.0, y);
      REQUIRE(s->verlet_info()->books_dissipation());
      const double i0 = sys.energy(y) - sys.verlet_term(y, h);
      double worst = 0.0;
      for (int i = 0; i < 5000; ++i) {
        REQUIRE(s->step(sys, 1e9) == pronk::ode::StepStatus::kOk);
        const double inv = sys.energy(s->y()) - sys.verlet_term(s->y(), h) +
                           s->verlet_info()->booked_dissipation();
        worst = std::max(worst, std::abs(inv - i0));
      }
      INFO("c = " << c << ", f = " << f << ": dissipated "
                  << s->verlet_info()->booked_dissipation());
      CHECK(worst < 1e-14 * (std::abs(i0) + 1.0));
      CHECK(s->verlet_info()->booked_dissipation() > 0.0);
    }
  }
}

TEST_CASE("verlet books with the held force: E - T_net + D is exact, T_net vanishes at a creep",
          "[ode][verlet]") {
  // With a kinetic-energy metric the stepper moves T - T_net from the booked dissipation to
  // the bounded term (T_net: the part of the force the damper does not cancel), keeping the
  // invariant exact. T_net is reconstructed here from the damper law, not from the stepper.
  for (const double c : {0.1, 10.0, 5e3}) {
    for (const double f : {0.0, 3.0}) {
      const double m = 0.2, k = 1280.0, h = 2e-3;  // omega h = 1.6
      const SplitSpring sys(m, k, c, f, true);
      auto s = make_stepper(verlet(h), 2);
      Vec y(2);
      y << 0.05, 0.4;
      s->reset(sys, 0.0, y);
      REQUIRE(s->step(sys, 1e9) == pronk::ode::StepStatus::kOk);  // from a closing half step on
      const double i0 =
          sys.energy(s->y()) - sys.held_term(s->y(), h) + s->verlet_info()->booked_dissipation();
      double worst = 0.0, worst_term = 0.0;
      for (int i = 0; i < 5000; ++i) {
        REQUIRE(s->step(sys, 1e9) == pronk::ode::StepStatus::kOk);
        const double inv =
            sys.energy(s->y()) - sys.held_term(s->y(), h) + s->verlet_info()->booked_dissipation();
        worst = std::max(worst, std::abs(inv - i0));
        worst_term = std::max(worst_term,
                              std::abs(s->verlet_info()->verlet_term() - sys.held_term(s->y(), h)));
      }
      INFO("c = " << c << ", f = " << f << ": dissipated "
                  << s->verlet_info()->booked_dissipation());
      CHECK(worst < 1e-14 * (std::abs(i0) + 1.0));
      CHECK(worst_term < 1e-15 * (std::abs(i0) + 1.0));
      // Fixed step: the step sizes differ by round-off only.
      CHECK(std::abs(s->verlet_info()->switching_offset()) < 1e-14 * (std::abs(i0) + 1.0));
    }
  }
  // A mass pushed against the damper (no spring) creeps at F / c: the damper cancels the
  // push, so T_net = 0 (the kicks' force alone would give h^2 F^2 / 8m = 1e-4 J) and the
  // booked dissipation per step is the damper's work F^2 / c h.
  const double m = 0.01, c = 500.0, f = 2.0, h = 2e-3;
  const SplitSpring push(m, 0.0, c, f, true);
  auto s = make_stepper(verlet(h), 2);
  Vec y(2);
  y << 0.0, 0.0;
  s->reset(push, 0.0, y);
  for (int i = 0; i < 200; ++i) REQUIRE(s->step(push, 1e9) == pronk::ode::StepStatus::kOk);
  CHECK(s->verlet_info()->verlet_term() < 1e-20);
  const double d0 = s->verlet_info()->booked_dissipation();
  s->step(push, 1e9);
  CHECK((s->verlet_info()->booked_dissipation() - d0) / h == Approx(f * f / c).epsilon(1e-9));
}

TEST_CASE("verlet with an energy budget keeps E - T_net + D - offset exact through its switches",
          "[ode][verlet]") {
  // Sub-steps refined from the first step on (a start with a large spring force), grid steps
  // cut short by off-grid limits, restarts: the stepper's own term and switching offset close
  // the invariant to round-off at every step, and the term stays within the budget.
  const double m = 0.2, k = 1280.0, c = 0.5, h = 4e-3, budget = 1e-6;
  const SplitSpring sys(m, k, c, 0.0, true);
  SolverOptions o = verlet(h);
  o.verlet_energy_budget = budget;
  auto s = make_stepper(o, 2);
  Vec y(2);
  y << 0.05, 0.0;
  s->reset(sys, 0.0, y);
  const pronk::ode::VerletInfo& v = *s->verlet_info();
  auto invariant = [&] { return verlet_invariant(sys, *s); };
  const double i0 = invariant(), e0 = sys.energy(y);
  double worst = 0.0, worst_term = 0.0, limit = 0.0;
  for (int call = 0; call < 400; ++call) {
    limit += 0.37 * h;  // off the grid: most grid steps are cut somewhere
    while (s->t() < limit) {
      REQUIRE(s->step(sys, limit) == pronk::ode::StepStatus::kOk);
      worst = std::max(worst, std::abs(invariant() - i0));
      worst_term = std::max(worst_term, v.verlet_term());
    }
    CHECK(s->t() == limit);
    if (call % 50 == 49) s->reset(sys, s->t(), s->y());  // restarts keep it exact too
  }
  INFO("steps " << s->counters().steps_accepted << ", rejected " << s->counters().steps_rejected);
  CHECK(worst < 1e-13 * e0);
  CHECK(worst_term <= budget);
  CHECK(s->counters().steps_rejected > 0);  // the first step was refined
}

TEST_CASE("verlet's held-force booking and energy budget do not depend on the frame",
          "[ode][verlet]") {
  // A mass on an anisotropic spring (1000 and 100 N/m along the body axes) with an isotropic
  // damper, the same motion in two frames rotated by 0.7 rad: with momentum blocks of two the
  // projection acts on the force vector, so steps, rejections and booked dissipation agree
  // to round-off.
  class Rotated final : public MechanicalSystem {
   public:
    explicit Rotated(double angle) {
      r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
      k = r * Eigen::Vector2d(1000.0, 100.0).asDiagonal() * r.transpose();
    }
    int dimension() const override { return 4; }
    void rhs(double t, const Vec& y, Vec& dydt) const override {
      conservative_rhs(t, y, dydt);
      dydt.tail<2>() -= c * y.tail<2>() / m;
    }
    void momentum_mask(Vec& mask) const override {
      mask.resize(4);
      mask << 0.0, 0.0, 1.0, 1.0;
    }
    void position_rate(const Vec& y, Vec& dydt) const override { dydt.head<2>() = y.tail<2>() / m; }
    bool has_dissipation_split() const override { return true; }
    void conservative_rhs(double, const Vec& y, Vec& dydt) const override {
      dydt.head<2>() = y.tail<2>() / m;
      dydt.tail<2>() = -k * y.head<2>();
    }
    double dissipate(double, double h, const Vec& y_ref, Vec& y) const override {
      const Eigen::Vector2d p0 = y.tail<2>();
      y.tail<2>() = p0 / (1.0 + h * c / m);
      const Eigen::Vector2d dp = y.tail<2>() - p0;
      return -dp.dot(y_ref.tail<2>() + 0.5 * dp) / m;
    }
    double kinetic_energy(const Vec& y) const override {
      return y.tail<2>().squaredNorm() / (2.0 * m);
    }
    int momentum_block() const override { return 2; }
    Eigen::Matrix2d r, k;     ///< rotation; stiffness [N/m]
    double m = 0.1, c = 3.0;  ///< [kg], [N s/m]
  };
  struct Run {
    long steps, rejected;
    double dissipated;
    Eigen::Vector2d q;  ///< final position in the body frame [m]
  };
  auto run = [](double angle) {
    const Rotated sys(angle);
    SolverOptions o = verlet(2e-3);
    o.verlet_energy_budget = 1e-5;
    auto s = make_stepper(o, 4);
    Vec y(4);
    y.head<2>() = sys.r * Eigen::Vector2d(0.05, 0.03);
    y.tail<2>() = sys.r * Eigen::Vector2d(0.0, 0.1);
    s->reset(sys, 0.0, y);
    while (s->t() < 4.0) REQUIRE(s->step(sys, 4.0) == pronk::ode::StepStatus::kOk);
    return Run{s->counters().steps_accepted, s->counters().steps_rejected,
               s->verlet_info()->booked_dissipation(), sys.r.transpose() * s->y().head<2>()};
  };
  const Run a = run(0.0), b = run(0.7);
  CHECK(a.steps == b.steps);
  CHECK(a.rejected == b.rejected);
  CHECK(a.rejected > 0);
  CHECK(b.dissipated == Approx(a.dissipated).epsilon(1e-10));
  CHECK((b.q - a.q).norm() < 1e-12);
}

TEST_CASE("verlet with a dissipation split creeps at F / c under a stiff damper", "[ode][verlet]") {
  // A mass pushed by F against a damper c (no spring): the velocity tends to F / c. With
  // h c / m = 100 the damper is far beyond any explicit method's stability limit; the
  // split scheme reaches the exact creep speed (a Strang splitting of the damper would
  // drift at h F / 2m, 50x too fast), and the unsplit Verlet blows up.
  const double m = 0.01, c = 500.0, f = 2.0, h = 2e-3;
  const SplitSpring split(m, 0.0, c, f);
  auto s = make_stepper(verlet(h), 2);
  Vec y(2);
  y << 0.0, 0.0;
  s->reset(split, 0.0, y);
  for (int i = 0; i < 200; ++i) REQUIRE(s->step(split, 1e9) == pronk::ode::StepStatus::kOk);
  CHECK(s->y()[1] / m == Approx(f / c).epsilon(1e-12));
  // Booked dissipation at the creep: the damper's power F^2 / c, per step.
  const double d0 = s->verlet_info()->booked_dissipation();
  s->step(split, 1e9);
  CHECK((s->verlet_info()->booked_dissipation() - d0) / h == Approx(f * f / c).epsilon(1e-9));

  const MassSpring unsplit(m, 0.0, c);
  auto u = make_stepper(verlet(h), 2);
  y << 0.0, 1e-3;
  u->reset(unsplit, 0.0, y);
  for (int i = 0; i < 50; ++i) u->step(unsplit, 1e9);
  CHECK_FALSE(std::abs(u->y()[1]) < 1.0);  // |p| grew by 100^50 (or overflowed)
  CHECK_FALSE(u->verlet_info()->books_dissipation());
}

TEST_CASE("verlet with a dissipation split converges to the damped oscillator", "[ode][verlet]") {
  // The damper is first order (backward Euler halves), the rest second: the error falls
  // linearly.
  const double m = 2.0, k = 50.0, c = 0.3;
  const SplitSpring split(m, k, c, 0.0);
  const MassSpring exact(m, k, c);
  auto error = [&](double h) {
    auto s = make_stepper(verlet(h), 2);
    Vec y(2);
    y << 1.0, 0.0;
    s->reset(split, 0.0, y);
    integrate(split, *s, 3.0, {}, verlet(h));
    return std::abs(s->y()[0] - exact.exact(3.0));
  };
  // (At h = 0.01 ... 0.005 the second-order phase error and the first-order damping
  // error still partly cancel; the order shows from h = 0.0025 on.)
  const double e1 = error(0.0025), e2 = error(0.00125);
  INFO("errors " << e1 << ", " << e2);
  CHECK(std::log2(e1 / e2) > 0.8);
  CHECK(std::log2(e1 / e2) < 1.2);
  CHECK(e2 < 2e-4);
}

TEST_CASE("verlet restarts at an event from its own step cut there, keeping E - T_net + D exact",
          "[ode][verlet]") {
  // A damped spring under a push, an event at every crossing of x = 0.01 (the restarts a
  // robot's touchdowns make). Restarting from the step retaken to the event keeps the run a
  // verlet trajectory (steps of varying size), so the invariant E - T_net + D - offset stays
  // exact to round-off through every restart; the dense output's state at the event is not
  // one verlet reaches, so restarting there moves the invariant at every event.
  struct Crossing final : pronk::ode::EventFunction {
    double value(double, const Vec& y) const override { return y[0] - 0.01; }
    int direction() const override { return 0; }
  } crossing;
  const pronk::ode::EventFunction* events[] = {&crossing};
  const double m = 0.2, k = 1280.0, c = 0.5, f = 2.0, h = 2e-3;
  const SplitSpring sys(m, k, c, f, true);
  auto run = [&](pronk::ode::EventRestart restart, long* n_events, long* accepted) {
    SolverOptions o = verlet(h);
    o.event_restart = restart;
    auto s = make_stepper(o, 2);
    Vec y(2);
    y << 0.05, 0.0;
    s->reset(sys, 0.0, y);
    auto invariant = [&] { return verlet_invariant(sys, *s); };
    const double i0 = invariant();
    double worst = 0.0;
    *n_events = 0;
    while (s->t() < 2.0) {
      const auto r = integrate(sys, *s, 2.0, events, o);
      worst = std::max(worst, std::abs(invariant() - i0));
      if (r.reason != pronk::ode::StopReason::kEvent) break;
      ++*n_events;
      CHECK(s->t() == r.t);  // the retaken (or interpolated) state is at the event time
    }
    *accepted = s->counters().steps_accepted;
    return worst / sys.energy(y);
  };
  long events_step = 0, events_dense = 0, accepted_step = 0, accepted_dense = 0;
  const double drift_step = run(pronk::ode::EventRestart::kStep, &events_step, &accepted_step);
  const double drift_dense =
      run(pronk::ode::EventRestart::kInterpolant, &events_dense, &accepted_dense);
  INFO("events " << events_step << " / " << events_dense << ", relative drift " << drift_step
                 << " / " << drift_dense);
  CHECK(events_step >= 10);
  CHECK(events_dense == events_step);
  CHECK(accepted_step == accepted_dense);  // a retaken step replaces the step, not adds one
  CHECK(drift_step < 1e-13);
  CHECK(drift_dense > 1e3 * drift_step);
}
