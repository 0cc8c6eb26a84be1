// Dormand-Prince 5(4) with FSAL, Hairer's PI step-size control, Hairer's
// automatic initial step and the 4th-order continuous extension ("contd5").
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "sim/ode/step_size_controller.hpp"
#include "sim/ode/steppers.hpp"

namespace pronk::ode::detail {
namespace {

// Butcher tableau (Dormand & Prince 1980; Hairer, Norsett & Wanner, table II.5.2).
constexpr double c2 = 1.0 / 5.0, c3 = 3.0 / 10.0, c4 = 4.0 / 5.0, c5 = 8.0 / 9.0;
constexpr double a21 = 1.0 / 5.0;
constexpr double a31 = 3.0 / 40.0, a32 = 9.0 / 40.0;
constexpr double a41 = 44.0 / 45.0, a42 = -56.0 / 15.0, a43 = 32.0 / 9.0;
constexpr double a51 = 19372.0 / 6561.0, a52 = -25360.0 / 2187.0, a53 = 64448.0 / 6561.0,
                 a54 = -212.0 / 729.0;
constexpr double a61 = 9017.0 / 3168.0, a62 = -355.0 / 33.0, a63 = 46732.0 / 5247.0,
                 a64 = 49.0 / 176.0, a65 = -5103.0 / 18656.0;
constexpr double a71 = 35.0 / 384.0, a73 = 500.0 / 1113.0, a74 = 125.0 / 192.0,
                 a75 = -2187.0 / 6784.0, a76 = 11.0 / 84.0;
// Error weights b - b_hat.
constexpr double e1 = 71.0 / 57600.0, e3 = -71.0 / 16695.0, e4 = 71.0 / 1920.0,
                 e5 = -17253.0 / 339200.0, e6 = 22.0 / 525.0, e7 = -1.0 / 40.0;
// Dense output weights (Hairer's dopri5.f, contd5).
constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                 d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                 d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;

// Step-size control (Hairer's defaults): safety 0.9, h_new / h in [0.2, 10], PI (Lund
// stabilisation) exponents.
constexpr double kBeta = 0.04;
const StepSizeController::Params kDopri5Control{.safety = 0.9,
                                                .quot_min = 1.0 / 10.0,
                                                .quot_max = 1.0 / 0.2,
                                                .exponent = 0.2 - kBeta * 0.75,
                                                .err_floor = 0.0,
                                                .beta = kBeta};

class Dopri5Stepper final : public Stepper {
 public:
  Dopri5Stepper(const SolverOptions& options, int n, ErrorNorm norm)
      : rtol_(options.rtol),
        atol_(options.atol),
        norm_(std::move(norm)),
        control_(kDopri5Control, options),
        y_(Vec::Zero(n)),
        y_prev_(Vec::Zero(n)),
        y_new_(Vec::Zero(n)),
        y_tmp_(Vec::Zero(n)) {
    for (Vec& k : k_) k = Vec::Zero(n);
    for (Vec& r : r_) r = Vec::Zero(n);
  }

  void reset(const OdeSystem& sys, double t, const Vec& y) override {
    assert(y.size() == y_.size());
    t_ = t;
    t_prev_ = t;
    h_last_ = 0.0;
    y_ = y;
    y_prev_ = y;
    sys.rhs(t_, y_, k_[0]);  // FSAL stage: y may have jumped
    ++counters_.rhs_evaluations;
    control_.choose_initial([&] { return initial_step(sys); });
  }

  StepStatus step(const OdeSystem& sys, double t_limit) override {
    if (!(t_limit > t_)) return StepStatus::kOk;
    return control_.step(
        t_, t_limit, counters_, [&](double h, double t_new) { return attempt(sys, h, t_new); },
        [&](double h, double t_new) { accept(h, t_new); });
  }

  void dense(double t, Vec& y_out) const override {
    y_out.resize(y_.size());
    if (!(h_last_ > 0.0)) {
      y_out = y_;
      return;
    }
    if (!dense_ready_) build_dense();
    const double s = (t - t_prev_) / h_last_;
    const double s1 = 1.0 - s;
    const double b3 = s * s1;
    const double b4 = b3 * s;
    const double b5 = b4 * s1;
    y_out.noalias() = y_prev_ + s * r_[0] + b3 * r_[1] + b4 * r_[2] + b5 * r_[3];
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override { return control_.h(); }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }

 private:
  /// One trial step of size h from (t_, y_) into y_new_, k_[1..6]; returns the
  /// RMS scaled error norm (non-finite if the state or the estimate is).
  double attempt(const OdeSystem& sys, double h, double t_new) {
    const Vec& k1 = k_[0];
    Vec &k2 = k_[1], &k3 = k_[2], &k4 = k_[3], &k5 = k_[4], &k6 = k_[5], &k7 = k_[6];
    y_tmp_.noalias() = y_ + (h * a21) * k1;
    sys.rhs(t_ + c2 * h, y_tmp_, k2);
    y_tmp_.noalias() = y_ + (h * a31) * k1 + (h * a32) * k2;
    sys.rhs(t_ + c3 * h, y_tmp_, k3);
    y_tmp_.noalias() = y_ + (h * a41) * k1 + (h * a42) * k2 + (h * a43) * k3;
    sys.rhs(t_ + c4 * h, y_tmp_, k4);
    y_tmp_.noalias() = y_ + (h * a51) * k1 + (h * a52) * k2 + (h * a53) * k3 + (h * a54) * k4;
    sys.rhs(t_ + c5 * h, y_tmp_, k5);
    y_tmp_.noalias() =
        y_ + (h * a61) * k1 + (h * a62) * k2 + (h * a63) * k3 + (h * a64) * k4 + (h * a65) * k5;
    sys.rhs(t_new, y_tmp_, k6);
    y_new_.noalias() =
        y_ + (h * a71) * k1 + (h * a73) * k3 + (h * a74) * k4 + (h * a75) * k5 + (h * a76) * k6;
    counters_.rhs_evaluations += 5;
    if (!y_new_.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    sys.rhs(t_new, y_new_, k7);
    ++counters_.rhs_evaluations;
    // Error estimate into y_tmp_, then its norm.
    y_tmp_.noalias() = (h * e1) * k1 + (h * e3) * k3 + (h * e4) * k4 + (h * e5) * k5 +
                       (h * e6) * k6 + (h * e7) * k7;
    return norm_(y_tmp_, y_, y_new_, rtol_, atol_);
  }

  /// Commits the trial step: FSAL swaps k7 into k1 (old k1 kept in k_[6]).
  void accept(double h, double t_new) {
    y_prev_.swap(y_);
    y_.swap(y_new_);
    k_[0].swap(k_[6]);
    t_prev_ = t_;
    t_ = t_new;
    h_last_ = h;
    dense_ready_ = false;
    ++counters_.steps_accepted;
  }

  /// Coefficients of the continuous extension of the last accepted step.
  void build_dense() const {
    const Vec& f0 = k_[6];  // f(t_prev, y_prev)
    const Vec& f1 = k_[0];  // f(t, y)
    const double h = h_last_;
    r_[0].noalias() = y_ - y_prev_;
    r_[1].noalias() = h * f0 - r_[0];
    r_[2].noalias() = r_[0] - h * f1 - r_[1];
    r_[3].noalias() = (h * d1) * f0 + (h * d3) * k_[2] + (h * d4) * k_[3] + (h * d5) * k_[4] +
                      (h * d6) * k_[5] + (h * d7) * f1;
    dense_ready_ = true;
  }

  /// Hairer's automatic initial step (hinit of dopri5.f, order 5); k_[0] = f(t_, y_).
  double initial_step(const OdeSystem& sys) {
    const Vec& f0 = k_[0];
    const Eigen::Index n = y_.size();
    double dnf = 0.0;
    double h = StepSizeController::first_guess(y_, f0, rtol_, atol_, &dnf);
    h = std::min(h, control_.h_max());
    y_tmp_.noalias() = y_ + h * f0;
    sys.rhs(t_ + h, y_tmp_, k_[1]);
    ++counters_.rhs_evaluations;
    double der2 = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double sk = atol_ + rtol_ * std::abs(y_[i]);
      const double q = (k_[1][i] - f0[i]) / sk;
      der2 += q * q;
    }
    der2 = std::sqrt(der2) / h;
    const double der12 = std::max(der2, std::sqrt(dnf));
    if (!std::isfinite(der12)) return std::max(std::min(h, 1e-6), control_.h_min());
    const double h1 = der12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / der12, 0.2);
    return std::min({100.0 * h, h1, control_.h_max()});
  }

  double rtol_, atol_;
  ErrorNorm norm_;
  StepSizeController control_;  ///< the adapted step and its PI control
  double t_ = 0.0;              ///< current time [s]
  double t_prev_ = 0.0;         ///< start of the last accepted step [s]
  double h_last_ = 0.0;         ///< size of the last accepted step; 0 after reset [s]
  Vec y_, y_prev_, y_new_, y_tmp_;
  Vec k_[7];          ///< stages; after accept k_[0] = f(t, y), k_[6] = f(t_prev, y_prev)
  mutable Vec r_[4];  ///< dense output coefficients (built lazily)
  mutable bool dense_ready_ = false;
  SolverCounters counters_;
};

}  // namespace

std::unique_ptr<Stepper> make_dopri5_stepper(const SolverOptions& options, int n, ErrorNorm norm) {
  return std::make_unique<Dopri5Stepper>(options, n, std::move(norm));
}

}  // namespace pronk::ode::detail
