// RADAU5: the 3-stage Radau IIA collocation method of order 5 (stage order 3,
// L-stable, stiffly accurate) in the form of Hairer & Wanner's code RADAU5
// (Solving ODEs II, sec. IV.8): the 3n stage equations are solved by a
// simplified Newton iteration that the eigen-decomposition of the inverse
// Butcher matrix splits into one real and one complex n x n system; the error
// estimate is filtered through (gamma/h - J)^-1; dense output is the
// collocation polynomial; the Jacobian and the factorisations are reused while
// the Newton iteration converges fast.
//
// Why pronk has it next to RODAS4: a Rosenbrock method linearises the stiff
// forces once per step. For stiff springs that rotate (every spinning or
// swinging pseudo-rigid body) the spring direction turns by omega*h within a
// step, and the error of that linearisation, of order k (v h)^2 / l, dwarfs
// the physical forces: RODAS4 then either resolves the internal vibration or
// loses the body's angular velocity (measured: satellite k = 1e6 N/m, 2763
// steps, omega error 7 %). A fully implicit method solves the stage equations
// with the nonlinear forces themselves and steps over the vibration.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <complex>
#include <limits>

#include "sim/ode/step_size_controller.hpp"
#include "sim/ode/steppers.hpp"
#include "sim/ode/stiff_linear_algebra.hpp"

namespace pronk::ode::detail {
namespace {

using Cplx = std::complex<double>;
using CVec = Eigen::VectorXcd;

/// The method's constants (Hairer's RADAU5, computed once).
struct Radau5Constants {
  double c1, c2, c1m1, c2m1, c1mc2;
  double dd1, dd2, dd3;
  double u1, alph, beta;  ///< eigenvalues gamma, alpha +- i beta of A^-1
  double t11 = 9.1232394870892942792e-02, t12 = -0.14125529502095420843,
         t13 = -3.0029194105147424492e-02;
  double t21 = 0.24171793270710701896, t22 = 0.20412935229379993199, t23 = 0.38294211275726193779;
  double t31 = 0.96604818261509293619;
  double ti11 = 4.3255798900631553510, ti12 = 0.33919925181580986954, ti13 = 0.54177053993587487119;
  double ti21 = -4.1787185915519047273, ti22 = -0.32768282076106238708,
         ti23 = 0.47662355450055045196;
  double ti31 = -0.50287263494578687595, ti32 = 2.5719269498556054292,
         ti33 = -0.59603920482822492497;

  Radau5Constants() {
    const double sq6 = std::sqrt(6.0);
    c1 = (4.0 - sq6) / 10.0;
    c2 = (4.0 + sq6) / 10.0;
    c1m1 = c1 - 1.0;
    c2m1 = c2 - 1.0;
    c1mc2 = c1 - c2;
    dd1 = -(13.0 + 7.0 * sq6) / 3.0;
    dd2 = (-13.0 + 7.0 * sq6) / 3.0;
    dd3 = -1.0 / 3.0;
    const double c81 = std::cbrt(81.0), c9 = std::cbrt(9.0);
    u1 = (6.0 + c81 - c9) / 30.0;
    alph = (12.0 - c81 + c9) / 60.0;
    beta = (c81 + c9) * std::sqrt(3.0) / 60.0;
    const double cno = alph * alph + beta * beta;
    u1 = 1.0 / u1;
    alph /= cno;
    beta /= cno;
    // A^-1 = T Lambda T^-1 with Lambda = [u1 0 0; 0 alph -beta; 0 beta alph] (the transformed
    // Newton systems below), and A.
    Eigen::Matrix3d t, ti, lambda;
    t << t11, t12, t13, t21, t22, t23, t31, 1.0, 0.0;
    ti << ti11, ti12, ti13, ti21, ti22, ti23, ti31, ti32, ti33;
    lambda << u1, 0.0, 0.0, 0.0, alph, -beta, 0.0, beta, alph;
    a_inv = t * lambda * ti;
    a = a_inv.inverse();
  }
  Eigen::Matrix3d a, a_inv;  ///< the Butcher matrix of Radau IIA and its inverse
};

const Radau5Constants& k() {
  static const Radau5Constants constants;
  return constants;
}

// Controller constants (RADAU5 defaults).
constexpr int kNit = 7;         ///< Newton iterations per attempt
constexpr double kSafe = 0.9;   ///< safety factor
constexpr double kThet = 1e-3;  ///< Newton rate below which the Jacobian is reused
/// h_new = h / clamp(err^(1/4) / fac, 1/8, 5) with fac <= kSafe by the Newton iterations
/// taken, and Gustafsson's predictive controller; the error is at least 1e-10 already.
const StepSizeController::Params kRadau5Control{.safety = kSafe,
                                                .quot_min = 1.0 / 8.0,
                                                .quot_max = 5.0,
                                                .exponent = 0.25,
                                                .err_floor = 0.0,
                                                .predictive = true};
constexpr double kQuot1 = 1.0, kQuot2 = 1.2;  ///< keep h (and the LU) if hnew/h is in here
constexpr int kMaxFailures = 40;              ///< consecutive failed attempts before giving up
/// Accepted steps of a stage-Jacobian period (radau5_stage_jacobians) before the cheaper
/// shared Jacobian is tried again.
constexpr int kMinStageSpan = 16, kMaxStageSpan = 1024;

class Radau5Stepper final : public Stepper {
 public:
  Radau5Stepper(const SolverOptions& options, int n, ErrorNorm norm)
      : norm_(std::move(norm)),
        control_(kRadau5Control, options),
        n_(n),
        lu1_(n <= options.dense_lu_max_dimension),
        lu2_(n <= options.dense_lu_max_dimension),
        stage_lu_(k().a, k().a_inv),
        stage_option_(options.radau5_stage_jacobians && n <= options.dense_lu_max_dimension) {
    // RADAU5 maps the user's tolerances to the ones its order-3 error
    // estimate needs (rtol' = 0.1 rtol^(2/3), atol' = rtol' atol / rtol).
    const double quot = options.atol / options.rtol;
    rtol_ = 0.1 * std::pow(options.rtol, 2.0 / 3.0);
    atol_ = rtol_ * quot;
    const double eps = std::numeric_limits<double>::epsilon();
    fnewt_ = std::max(10.0 * eps / rtol_, std::min(0.03, std::sqrt(rtol_)));
    for (Vec* v : {&y_, &y_new_, &f0_, &tmp_, &scal_, &z1_, &z2_, &z3_, &w1_, &w2_, &w3_, &g1_,
                   &g2_, &g3_, &cont1_, &cont2_, &cont3_, &err_}) {
      *v = Vec::Zero(n);
    }
    cz_ = CVec::Zero(n);
  }

  void reset(const OdeSystem& sys, double t, const Vec& y) override {
    assert(y.size() == y_.size());
    lu1_.use_structure(sys);
    lu2_.use_structure(sys);
    stage_allowed_ = stage_option_ && sys.has_jacobian() && stage_lu_.use_structure(sys);
    if (!stage_allowed_) stage_mode_ = false;
    t_ = t;
    t_prev_ = t;
    h_last_ = 0.0;
    y_ = y;
    sys.rhs(t_, y_, f0_);
    ++counters_.rhs_evaluations;
    jacobian_fresh_ = false;
    have_jacobian_ = false;
    first_ = true;
    control_.choose_initial([] { return 1e-6; });
  }

  StepStatus step(const OdeSystem& sys, double t_limit) override {
    if (!(t_limit > t_)) return StepStatus::kOk;
    bool reject = false;
    int failures = 0;
    if (!have_jacobian_) evaluate_jacobian(sys);
    for (int i = 0; i < n_; ++i) scal_[i] = atol_ + rtol_ * std::abs(y_[i]);
    for (;;) {
      if (failures > kMaxFailures) return StepStatus::kNonFinite;
      const StepSizeController::Trial tr = control_.trial(t_, t_limit);
      const double h = tr.h, t_new = tr.t_new;
      if (!(t_new > t_)) return StepStatus::kStepSizeCollapse;
      if (tr.h_adapted < control_.h_min()) return StepStatus::kStepSizeCollapse;

      // A failed attempt recomputes the Jacobian at the step start unless it is fresh.
      auto retry = [&](double h_next) {
        ++counters_.steps_rejected;
        reject = true;
        ++failures;
        control_.retry(h_next);  // (h_min is checked at the next attempt)
        if (!jacobian_fresh_) evaluate_jacobian(sys);
      };

      if (!factorize(h)) {
        retry(0.5 * h);
        continue;
      }
      start_stages(h);
      if (stage_mode_ && !factorize_stages(sys, h)) {
        retry(0.5 * h);
        continue;
      }
      int newt = 0;
      double h_slow = h;
      const NewtonOutcome outcome = newton(sys, h, t_new, &newt, &h_slow);
      if (outcome != NewtonOutcome::kConverged && !stage_mode_ && stage_allowed_) {
        enter_stage_mode();
        retry(h);  // the same step with a Jacobian per stage
        continue;
      }
      if (outcome == NewtonOutcome::kSlow) {
        retry(h_slow);
        continue;
      }
      if (outcome == NewtonOutcome::kFailed) {
        retry(0.5 * h);
        continue;
      }

      // Error estimate, filtered through (gamma/h - J)^-1.
      const double err = estimate_error(sys, h, reject);
      if (!std::isfinite(err)) {
        retry(0.5 * h);
        continue;
      }
      const double fac = std::min(kSafe, kSafe * (1.0 + 2.0 * kNit) / (newt + 2.0 * kNit));
      if (err < 1.0) {
        accept_and_adapt(sys, tr, err, fac, reject);
        return StepStatus::kOk;
      }
      retry(first_ ? 0.1 * h : h / control_.quotient(err, fac));
    }
  }

  void dense(double t, Vec& y_out) const override {
    y_out.resize(y_.size());
    if (!(h_last_ > 0.0)) {
      y_out = y_;
      return;
    }
    const auto& c = k();
    const double s = (t - t_) / h_last_;  // in [-1, 0]
    y_out = y_ + s * (cont1_ + (s - c.c2m1) * (cont2_ + (s - c.c1m1) * cont3_));
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override { return control_.h(); }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }

 private:
  enum class NewtonOutcome { kConverged, kSlow, kFailed };

  /// Starting values of the stages: the previous step's collocation polynomial, or zero.
  void start_stages(double h) {
    const auto& c = k();
    if (first_ || !(h_last_ > 0.0)) {
      z1_.setZero();
      z2_.setZero();
      z3_.setZero();
      w1_.setZero();
      w2_.setZero();
      w3_.setZero();
    } else {
      const double c3q = h / h_last_, c1q = c.c1 * c3q, c2q = c.c2 * c3q;
      z1_ = c1q * (cont1_ + (c1q - c.c2m1) * (cont2_ + (c1q - c.c1m1) * cont3_));
      z2_ = c2q * (cont1_ + (c2q - c.c2m1) * (cont2_ + (c2q - c.c1m1) * cont3_));
      z3_ = c3q * (cont1_ + (c3q - c.c2m1) * (cont2_ + (c3q - c.c1m1) * cont3_));
      w1_ = c.ti11 * z1_ + c.ti12 * z2_ + c.ti13 * z3_;
      w2_ = c.ti21 * z1_ + c.ti22 * z2_ + c.ti23 * z3_;
      w3_ = c.ti31 * z1_ + c.ti32 * z2_ + c.ti33 * z3_;
    }
  }

  /// The simplified Newton iteration on the stage equations of a step h to t_new; counts
  /// its iterations in *newt and, when it converges too slowly, proposes *h_slow.
  NewtonOutcome newton(const OdeSystem& sys, double h, double t_new, int* newt, double* h_slow) {
    const auto& c = k();
    const double fac1 = c.u1 / h, alphn = c.alph / h, betan = c.beta / h;
    faccon_ = std::pow(std::max(faccon_, std::numeric_limits<double>::epsilon()), 0.8);
    theta_ = kThet;
    double dynold = 0.0, thqold = 0.0;
    for (;;) {
      if (*newt >= kNit) break;
      tmp_ = y_ + z1_;
      sys.rhs(t_ + c.c1 * h, tmp_, g1_);
      tmp_ = y_ + z2_;
      sys.rhs(t_ + c.c2 * h, tmp_, g2_);
      tmp_ = y_ + z3_;
      sys.rhs(t_new, tmp_, g3_);
      counters_.rhs_evaluations += 3;
      if (!g1_.allFinite() || !g2_.allFinite() || !g3_.allFinite()) break;
      if (stage_mode_) {
        solve_stages(h);
      } else {
        // Right-hand sides of the transformed systems (stored in z1_, z2_, z3_).
        z1_ = c.ti11 * g1_ + c.ti12 * g2_ + c.ti13 * g3_ - fac1 * w1_;
        z2_ = c.ti21 * g1_ + c.ti22 * g2_ + c.ti23 * g3_ - alphn * w2_ + betan * w3_;
        z3_ = c.ti31 * g1_ + c.ti32 * g2_ + c.ti33 * g3_ - alphn * w3_ - betan * w2_;
        solve_real(z1_);
        solve_complex(z2_, z3_);
      }
      ++*newt;
      double dyno = 0.0;
      for (int i = 0; i < n_; ++i) {
        const double a = z1_[i] / scal_[i], b = z2_[i] / scal_[i], d = z3_[i] / scal_[i];
        dyno += a * a + b * b + d * d;
      }
      dyno = std::sqrt(dyno / (3.0 * n_));
      if (!std::isfinite(dyno)) break;
      if (*newt > 1 && *newt < kNit) {
        const double thq = dyno / dynold;
        theta_ = *newt == 2 ? thq : std::sqrt(thq * thqold);
        thqold = thq;
        if (theta_ < 0.99) {
          faccon_ = theta_ / (1.0 - theta_);
          const double dyth = faccon_ * dyno * std::pow(theta_, kNit - 1 - *newt) / fnewt_;
          if (dyth >= 1.0) {
            const double qnewt = std::clamp(dyth, 1e-4, 20.0);
            *h_slow = 0.8 * std::pow(qnewt, -1.0 / (4.0 + kNit - 1 - *newt)) * h;
            return NewtonOutcome::kSlow;
          }
        } else {
          break;  // diverging
        }
      }
      dynold = std::max(dyno, std::numeric_limits<double>::epsilon());
      w1_ += z1_;
      w2_ += z2_;
      w3_ += z3_;
      z1_ = c.t11 * w1_ + c.t12 * w2_ + c.t13 * w3_;
      z2_ = c.t21 * w1_ + c.t22 * w2_ + c.t23 * w3_;
      z3_ = c.t31 * w1_ + w2_;
      if (faccon_ * dyno <= fnewt_) return NewtonOutcome::kConverged;
    }
    return NewtonOutcome::kFailed;
  }

  /// Accepts the trial step of error err < 1 (Newton safety factor fac) and chooses the
  /// next step size (the predictive controller, not after a restart) and whether to keep the
  /// Jacobian.
  void accept_and_adapt(const OdeSystem& sys, const StepSizeController::Trial& tr, double err,
                        double fac, bool reject) {
    const double h = tr.h;
    double h_new = control_.bounded(control_.accepted(h, err, fac, !first_), h, reject);
    first_ = false;
    accept(sys, h, tr.t_new);
    count_mode_step();
    const double qt = h_new / h;
    if (theta_ <= kThet && qt >= kQuot1 && qt <= kQuot2) h_new = h;  // keep h and the LU
    control_.set_next(h_new, tr, reject);
    // Reuse the Jacobian while the Newton iteration converges this fast.
    if (theta_ <= kThet) {
      jacobian_fresh_ = false;
    } else {
      have_jacobian_ = false;
    }
  }

  /// The shared-Jacobian Newton failed (too slow or diverging): Newton with stage Jacobians
  /// for the next stage_span_ accepted steps. Failing again soon after a return to the shared
  /// Jacobian doubles the span (at most kMaxStageSpan); holding on for a full span resets it.
  void enter_stage_mode() {
    if (classic_steps_ < stage_span_) {
      if (classic_steps_ >= 0) stage_span_ = std::min(2 * stage_span_, kMaxStageSpan);
    } else {
      stage_span_ = kMinStageSpan;
    }
    stage_mode_ = true;
    stage_left_ = stage_span_;
  }

  /// After an accepted step: counts down the stage mode, then returns to the shared Jacobian
  /// (cheaper per step) to see whether it converges again.
  void count_mode_step() {
    if (!stage_mode_) {
      if (classic_steps_ >= 0) ++classic_steps_;
      return;
    }
    if (--stage_left_ > 0) return;
    stage_mode_ = false;
    classic_steps_ = 0;
    h_factored_ = -1.0;  // the complex factorisation was not kept up
  }

  void evaluate_jacobian(const OdeSystem& sys) {
    detail::evaluate_jacobian(sys, t_, y_, f0_, j_sparse_, tmp_, g1_, counters_);
    assert(j_sparse_.rows() == y_.size() && j_sparse_.cols() == y_.size());
    have_jacobian_ = true;
    jacobian_fresh_ = true;
    h_factored_ = -1.0;
  }

  /// Factorises E1 = (gamma/h) I - J and E2 = ((alpha + i beta)/h) I - J
  /// (counted as one factorisation of the iteration matrices); with stage Jacobians only E1,
  /// the error estimate's filter.
  bool factorize(double h) {
    if (h == h_factored_) return factorization_ok_;
    const auto& c = k();
    ++counters_.lu_factorizations;
    h_factored_ = h;
    const bool real_ok = lu1_.compute(j_sparse_, c.u1 / h);
    const bool complex_ok = stage_mode_ || lu2_.compute(j_sparse_, Cplx(c.alph / h, c.beta / h));
    factorization_ok_ = real_ok && complex_ok;
    return factorization_ok_;
  }

  /// Stage Jacobians at the starting values of the stages (start_stages) and the Newton
  /// matrix with them (StageLu); false when it is singular. A Jacobian that breaks the
  /// mechanical structure ends the stage mode for this stepper (the step is retried).
  bool factorize_stages(const OdeSystem& sys, double h) {
    const auto& c = k();
    const double cs[3] = {c.c1, c.c2, 1.0};
    const Vec* zs[3] = {&z1_, &z2_, &z3_};
    for (int i = 0; i < 3; ++i) {
      tmp_ = y_ + *zs[i];
      sys.jacobian(t_ + cs[i] * h, tmp_, j_stage_[static_cast<size_t>(i)]);
    }
    counters_.jacobian_evaluations += 3;
    ++counters_.lu_factorizations;
    if (stage_lu_.compute({&j_stage_[0], &j_stage_[1], &j_stage_[2]}, h)) return true;
    if (!stage_lu_.broken()) return false;
    stage_mode_ = stage_allowed_ = false;  // structure broken: the shared Jacobian from now on
    h_factored_ = -1.0;
    return false;
  }

  /// One Newton correction with the stage Jacobians: with g_i = f(stage i),
  /// M dZ = g - (A^-1 / h) Z, and the transformed correction dW = T^-1 dZ in z1_, z2_, z3_.
  void solve_stages(double h) {
    const auto& c = k();
    const Eigen::Matrix3d& ai = c.a_inv;
    const double ih = 1.0 / h;
    g1_ -= ih * (ai(0, 0) * z1_ + ai(0, 1) * z2_ + ai(0, 2) * z3_);
    g2_ -= ih * (ai(1, 0) * z1_ + ai(1, 1) * z2_ + ai(1, 2) * z3_);
    g3_ -= ih * (ai(2, 0) * z1_ + ai(2, 1) * z2_ + ai(2, 2) * z3_);
    stage_lu_.solve(g1_, g2_, g3_);
    z1_ = c.ti11 * g1_ + c.ti12 * g2_ + c.ti13 * g3_;
    z2_ = c.ti21 * g1_ + c.ti22 * g2_ + c.ti23 * g3_;
    z3_ = c.ti31 * g1_ + c.ti32 * g2_ + c.ti33 * g3_;
  }

  void solve_real(Vec& b) { lu1_.solve(b); }

  /// Solves E2 (re + i im) = (re + i im) in place.
  void solve_complex(Vec& re, Vec& im) {
    for (int i = 0; i < n_; ++i) cz_[i] = Cplx(re[i], im[i]);
    lu2_.solve(cz_);
    re = cz_.real();
    im = cz_.imag();
  }

  /// The error norm of e: the plain norm weighs by the step's start only (RADAU5's scal),
  /// any other sees both ends of the step.
  double norm_of(const Vec& e) const {
    if (norm_.is_plain()) {
      double sum = 0.0;
      for (int i = 0; i < n_; ++i) {
        const double q = e[i] / scal_[i];
        sum += q * q;
      }
      return std::sqrt(sum / std::max(1, n_));
    }
    tmp_ = y_ + z3_;
    return norm_(e, y_, tmp_, rtol_, atol_);
  }

  /// Hairer's estimate err = (gamma/h - J)^-1 (f0 + sum dd_i z_i / h), with one
  /// more filtering pass after a rejection or on the first step.
  double estimate_error(const OdeSystem& sys, double h, bool reject) {
    const auto& c = k();
    g2_ = (c.dd1 / h) * z1_ + (c.dd2 / h) * z2_ + (c.dd3 / h) * z3_;
    err_ = g2_ + f0_;
    solve_real(err_);
    double err = std::max(norm_of(err_), 1e-10);
    if (err >= 1.0 && (first_ || reject)) {
      tmp_ = y_ + err_;
      sys.rhs(t_, tmp_, g1_);
      ++counters_.rhs_evaluations;
      err_ = g1_ + g2_;
      solve_real(err_);
      err = std::max(norm_of(err_), 1e-10);
    }
    return err;
  }

  void accept(const OdeSystem& sys, double h, double t_new) {
    const auto& c = k();
    y_new_ = y_ + z3_;
    // Collocation polynomial in s = (t - t_new) / h, s in [-1, 0].
    cont1_ = (z2_ - z3_) / c.c2m1;
    g1_ = (z1_ - z2_) / c.c1mc2;  // ak
    g2_ = z1_ / c.c1;
    g2_ = (g1_ - g2_) / c.c2;  // acont3
    cont2_ = (g1_ - cont1_) / c.c1m1;
    cont3_ = cont2_ - g2_;
    y_.swap(y_new_);
    t_prev_ = t_;
    t_ = t_new;
    h_last_ = h;
    sys.rhs(t_, y_, f0_);
    ++counters_.rhs_evaluations;
    ++counters_.steps_accepted;
  }

  ErrorNorm norm_;
  StepSizeController control_;      ///< the adapted step and its predictive control
  double rtol_ = 0.0, atol_ = 0.0;  ///< transformed tolerances
  double fnewt_ = 0.0;              ///< Newton stopping tolerance
  int n_;
  double t_ = 0.0, t_prev_ = 0.0;  ///< [s]
  double h_last_ = 0.0;            ///< last accepted step, 0 after reset [s]
  double h_factored_ = -1.0;       ///< [s]
  double faccon_ = 1.0, theta_ = kThet;
  bool factorization_ok_ = false;
  bool first_ = true;
  bool have_jacobian_ = false;   ///< j_sparse_ holds a Jacobian (maybe of an earlier point)
  bool jacobian_fresh_ = false;  ///< ... evaluated at (t_, y_)
  Vec y_, y_new_, f0_, scal_, z1_, z2_, z3_, w1_, w2_, w3_, g1_, g2_, g3_, cont1_, cont2_, cont3_,
      err_;
  mutable Vec tmp_;
  CVec cz_;
  Eigen::SparseMatrix<double> j_sparse_;
  SolverCounters counters_;
  ShiftedLu<double> lu1_;  ///< (gamma/h) I - J
  ShiftedLu<Cplx> lu2_;    ///< ((alpha + i beta)/h) I - J
  StageLu stage_lu_;       ///< the Newton matrix with a Jacobian per stage
  std::array<Eigen::SparseMatrix<double>, 3> j_stage_;
  bool stage_option_;               ///< SolverOptions::radau5_stage_jacobians
  bool stage_allowed_ = false;      ///< ... and a mechanical system with an analytic Jacobian
  bool stage_mode_ = false;         ///< Newton with stage Jacobians now
  int stage_left_ = 0;              ///< accepted steps left in the stage mode
  int stage_span_ = kMinStageSpan;  ///< accepted steps of the next stage mode
  long classic_steps_ = -1;         ///< accepted shared-Jacobian steps since the last stage mode
                                    ///< (-1: never in it)
};

}  // namespace

std::unique_ptr<Stepper> make_radau5_stepper(const SolverOptions& options, int n, ErrorNorm norm) {
  return std::make_unique<Radau5Stepper>(options, n, std::move(norm));
}

}  // namespace pronk::ode::detail
