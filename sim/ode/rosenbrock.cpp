// RODAS4: the 6-stage, order 4(3), L-stable and stiffly accurate Rosenbrock
// method of Hairer & Wanner (Solving ODEs II, sec. IV.7), in the transformed
// formulation of their code RODAS, with its embedded error estimate (the last
// stage) and its 3rd-order dense output. The linear systems
// (I/(gamma h) - J) k = rhs use dense partial-pivoting LU for small systems and
// Eigen's SparseLU above SolverOptions::dense_lu_max_dimension (mechanical systems:
// the dense LU of the momentum Schur complement, half the size). The Jacobian is
// evaluated once per accepted base point (analytic when the system has one,
// forward differences otherwise) and reused across rejected attempts; only the
// factorisation is redone when h changes.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "sim/ode/step_size_controller.hpp"
#include "sim/ode/steppers.hpp"
#include "sim/ode/stiff_linear_algebra.hpp"

namespace pronk::ode::detail {
namespace {

// Transformed coefficients (Hairer's RODAS, METH = 1: RODAS4).
constexpr double kGamma = 0.25;
constexpr double c2 = 0.386, c3 = 0.21, c4 = 0.63;
constexpr double d1 = 0.25, d2 = -0.1043, d3 = 0.1035, d4 = -0.0362;
constexpr double a21 = 1.544;
constexpr double a31 = 0.9466785280815826, a32 = 0.2557011698983284;
constexpr double a41 = 3.314825187068521, a42 = 2.896124015972201, a43 = 0.9986419139977817;
constexpr double a51 = 1.221224509226641, a52 = 6.019134481288629, a53 = 12.53708332932087,
                 a54 = -0.687886036105895;
constexpr double c21 = -5.6688;
constexpr double c31 = -2.430093356833875, c32 = -0.2063599157091915;
constexpr double c41 = -0.1073529058151375, c42 = -9.594562251023355, c43 = -20.47028614809616;
constexpr double c51 = 7.496443313967647, c52 = -10.24680431464352, c53 = -33.99990352819905,
                 c54 = 11.7089089320616;
constexpr double c61 = 8.083246795921522, c62 = -7.981132988064893, c63 = -31.52159432874371,
                 c64 = 16.31930543123136, c65 = -6.058818238834054;
// Dense output.
constexpr double h21 = 10.12623508344586, h22 = -7.487995877610167, h23 = -34.80091861555747,
                 h24 = -7.992771707568823, h25 = 1.025137723295662;
constexpr double h31 = -0.6762803392801253, h32 = 6.087714651680015, h33 = 16.43084320892478,
                 h34 = 24.76722511418386, h35 = -6.594389125716872;

// Step-size control (RODAS defaults): h_new = h / clamp(err^(1/4) / safety, 1/6, 5),
// with Gustafsson's predictive controller after accepted steps.
const StepSizeController::Params kRodas4Control{.safety = 0.9,
                                                .quot_min = 1.0 / 6.0,
                                                .quot_max = 5.0,
                                                .exponent = 0.25,
                                                .err_floor = 1e-300,
                                                .predictive = true};

class Rodas4Stepper final : public Stepper {
 public:
  Rodas4Stepper(const SolverOptions& options, int n, ErrorNorm norm)
      : rtol_(options.rtol),
        atol_(options.atol),
        norm_(std::move(norm)),
        control_(kRodas4Control, options),
        y_(Vec::Zero(n)),
        y_prev_(Vec::Zero(n)),
        y_new_(Vec::Zero(n)),
        y_tmp_(Vec::Zero(n)),
        f0_(Vec::Zero(n)),
        fx_(Vec::Zero(n)),
        dy_(Vec::Zero(n)),
        r1_(Vec::Zero(n)),
        r2_(Vec::Zero(n)),
        lu_(n <= options.dense_lu_max_dimension) {
    for (Vec& k : k_) k = Vec::Zero(n);
  }

  void reset(const OdeSystem& sys, double t, const Vec& y) override {
    assert(y.size() == y_.size());
    lu_.use_structure(sys);
    t_ = t;
    t_prev_ = t;
    h_last_ = 0.0;
    y_ = y;
    y_prev_ = y;
    sys.rhs(t_, y_, f0_);
    ++counters_.rhs_evaluations;
    jacobian_current_ = false;
    control_.choose_initial([&] { return initial_step(); });
  }

  StepStatus step(const OdeSystem& sys, double t_limit) override {
    if (!(t_limit > t_)) return StepStatus::kOk;
    if (!jacobian_current_) evaluate_jacobian(sys);
    return control_.step(
        t_, t_limit, counters_, [&](double h, double t_new) { return attempt(sys, h, t_new); },
        [&](double h, double t_new) { accept(sys, h, t_new); });
  }

  void dense(double t, Vec& y_out) const override {
    y_out.resize(y_.size());
    if (!(h_last_ > 0.0)) {
      y_out = y_;
      return;
    }
    const double s = (t - t_prev_) / h_last_;
    const double s1 = 1.0 - s;
    y_out.noalias() = s1 * y_prev_ + s * (y_ + s1 * (r1_ + s * r2_));
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override { return control_.h(); }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }

 private:
  /// J = df/dy at (t_, y_) (analytic or forward differences) and df/dt.
  void evaluate_jacobian(const OdeSystem& sys) {
    detail::evaluate_jacobian(sys, t_, y_, f0_, j_sparse_, y_tmp_, dy_, counters_);
    assert(j_sparse_.rows() == y_.size() && j_sparse_.cols() == y_.size());
    if (sys.autonomous()) {
      fx_.setZero();
    } else {
      const double delta = std::sqrt(1e-16 * std::max(1e-5, std::abs(t_)));
      sys.rhs(t_ + delta, y_, dy_);
      ++counters_.rhs_evaluations;
      fx_ = (dy_ - f0_) / delta;
    }
    jacobian_current_ = true;
    h_factored_ = -1.0;
  }

  /// Factorises E = I/(gamma h) - J; false when singular or non-finite.
  bool factorize(double h) {
    if (h == h_factored_) return lu_.ok();
    ++counters_.lu_factorizations;
    h_factored_ = h;
    return lu_.compute(j_sparse_, 1.0 / (kGamma * h));
  }

  /// Solves E x = b in place.
  void solve(Vec& b) { lu_.solve(b); }

  /// One trial step; returns the scaled error (non-finite on failure).
  double attempt(const OdeSystem& sys, double h, double t_new) {
    if (!factorize(h)) return std::numeric_limits<double>::quiet_NaN();
    const double ih = 1.0 / h;
    Vec &k1 = k_[0], &k2 = k_[1], &k3 = k_[2], &k4 = k_[3], &k5 = k_[4], &k6 = k_[5];
    k1.noalias() = f0_ + (h * d1) * fx_;
    solve(k1);
    y_tmp_.noalias() = y_ + a21 * k1;
    sys.rhs(t_ + c2 * h, y_tmp_, dy_);
    k2.noalias() = dy_ + (h * d2) * fx_ + (c21 * ih) * k1;
    solve(k2);
    y_tmp_.noalias() = y_ + a31 * k1 + a32 * k2;
    sys.rhs(t_ + c3 * h, y_tmp_, dy_);
    k3.noalias() = dy_ + (h * d3) * fx_ + (c31 * ih) * k1 + (c32 * ih) * k2;
    solve(k3);
    y_tmp_.noalias() = y_ + a41 * k1 + a42 * k2 + a43 * k3;
    sys.rhs(t_ + c4 * h, y_tmp_, dy_);
    k4.noalias() = dy_ + (h * d4) * fx_ + (c41 * ih) * k1 + (c42 * ih) * k2 + (c43 * ih) * k3;
    solve(k4);
    y_tmp_.noalias() = y_ + a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4;
    sys.rhs(t_new, y_tmp_, dy_);
    k5.noalias() = dy_ + (c51 * ih) * k1 + (c52 * ih) * k2 + (c53 * ih) * k3 + (c54 * ih) * k4;
    solve(k5);
    y_new_.noalias() = y_tmp_ + k5;
    sys.rhs(t_new, y_new_, dy_);
    k6.noalias() = dy_ + (c61 * ih) * k1 + (c62 * ih) * k2 + (c63 * ih) * k3 + (c64 * ih) * k4 +
                   (c65 * ih) * k5;
    solve(k6);
    y_new_ += k6;
    counters_.rhs_evaluations += 5;
    if (!y_new_.allFinite() || !k6.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    return norm_(k6, y_, y_new_, rtol_, atol_);
  }

  void accept(const OdeSystem& sys, double h, double t_new) {
    // Dense output coefficients from the stages of this step.
    r1_.noalias() = h21 * k_[0] + h22 * k_[1] + h23 * k_[2] + h24 * k_[3] + h25 * k_[4];
    r2_.noalias() = h31 * k_[0] + h32 * k_[1] + h33 * k_[2] + h34 * k_[3] + h35 * k_[4];
    y_prev_.swap(y_);
    y_.swap(y_new_);
    t_prev_ = t_;
    t_ = t_new;
    h_last_ = h;
    sys.rhs(t_, y_, f0_);
    ++counters_.rhs_evaluations;
    jacobian_current_ = false;
    ++counters_.steps_accepted;
  }

  /// A cautious first step from the scale of f (Hairer's codes start at 1e-6 s
  /// without better information; the controller grows it quickly).
  double initial_step() const {
    const double h = StepSizeController::first_guess(y_, f0_, rtol_, atol_);
    return std::clamp(h, std::max(control_.h_min(), 1e-10), control_.h_max());
  }

  double rtol_, atol_;
  ErrorNorm norm_;
  StepSizeController control_;     ///< the adapted step and its predictive control
  double t_ = 0.0, t_prev_ = 0.0;  ///< current time, start of the last step [s]
  double h_last_ = 0.0;            ///< last accepted step; 0 after reset [s]
  double h_factored_ = -1.0;       ///< h of the current factorisation [s]
  bool jacobian_current_ = false;  ///< j_sparse_ belongs to (t_, y_)
  Vec y_, y_prev_, y_new_, y_tmp_;
  Vec f0_;  ///< f(t_, y_)
  Vec fx_;  ///< df/dt at (t_, y_)
  Vec dy_;
  Vec k_[6];     ///< stage solutions of the last attempt
  Vec r1_, r2_;  ///< dense output coefficients of the last accepted step
  Eigen::SparseMatrix<double> j_sparse_;
  ShiftedLu<double> lu_;  ///< I/(gamma h) - J, dense (small systems) or SparseLU
  SolverCounters counters_;
};

}  // namespace

std::unique_ptr<Stepper> make_rodas4_stepper(const SolverOptions& options, int n, ErrorNorm norm) {
  return std::make_unique<Rodas4Stepper>(options, n, std::move(norm));
}

}  // namespace pronk::ode::detail
