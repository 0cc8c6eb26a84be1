// Fixed-step explicit Runge-Kutta methods (Euler, RK2 midpoint, RK4) with
// cubic Hermite dense output built from f at both step ends.
#include <cassert>
#include <cmath>

#include "sim/ode/steppers.hpp"

namespace pronk::ode::detail {
namespace {

class ExplicitRkStepper final : public Stepper {
 public:
  ExplicitRkStepper(const SolverOptions& options, int n)
      : method_(options.method),
        h_fixed_(options.h_fixed),
        y_(Vec::Zero(n)),
        y_prev_(Vec::Zero(n)),
        y_new_(Vec::Zero(n)),
        y_tmp_(Vec::Zero(n)),
        f_(Vec::Zero(n)),
        f_prev_(Vec::Zero(n)),
        f_new_(Vec::Zero(n)),
        k2_(Vec::Zero(n)),
        k3_(Vec::Zero(n)),
        k4_(Vec::Zero(n)) {}

  void reset(const OdeSystem& sys, double t, const Vec& y) override {
    assert(y.size() == y_.size());
    t_ = t;
    t_prev_ = t;
    t_base_ = t;
    steps_since_base_ = 0;
    y_ = y;
    y_prev_ = y;
    sys.rhs(t_, y_, f_);
    f_prev_ = f_;
    ++counters_.rhs_evaluations;
  }

  StepStatus step(const OdeSystem& sys, double t_limit) override {
    if (!(t_limit > t_)) return StepStatus::kOk;
    // Grid time relative to the last base point avoids accumulating round-off.
    double t_new = t_base_ + static_cast<double>(steps_since_base_ + 1) * h_fixed_;
    const bool last = t_new >= t_limit - 1e-9 * h_fixed_;
    if (last) t_new = t_limit;
    const double h = t_new - t_;
    if (!(h > 0.0)) return StepStatus::kStepSizeCollapse;

    switch (method_) {
      case Method::kEuler:
        y_new_.noalias() = y_ + h * f_;
        break;
      case Method::kRk2:
        y_tmp_.noalias() = y_ + (0.5 * h) * f_;
        sys.rhs(t_ + 0.5 * h, y_tmp_, k2_);
        ++counters_.rhs_evaluations;
        y_new_.noalias() = y_ + h * k2_;
        break;
      default:  // kRk4
        y_tmp_.noalias() = y_ + (0.5 * h) * f_;
        sys.rhs(t_ + 0.5 * h, y_tmp_, k2_);
        y_tmp_.noalias() = y_ + (0.5 * h) * k2_;
        sys.rhs(t_ + 0.5 * h, y_tmp_, k3_);
        y_tmp_.noalias() = y_ + h * k3_;
        sys.rhs(t_new, y_tmp_, k4_);
        counters_.rhs_evaluations += 3;
        y_new_.noalias() = y_ + (h / 6.0) * (f_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
        break;
    }
    if (!y_new_.allFinite()) {
      ++counters_.steps_rejected;
      return StepStatus::kNonFinite;
    }
    // f at the new point: Hermite dense output now, first stage of the next step.
    sys.rhs(t_new, y_new_, f_new_);
    ++counters_.rhs_evaluations;

    y_prev_.swap(y_);
    y_.swap(y_new_);
    f_prev_.swap(f_);
    f_.swap(f_new_);
    t_prev_ = t_;
    t_ = t_new;
    if (last) {
      t_base_ = t_;
      steps_since_base_ = 0;
    } else {
      ++steps_since_base_;
    }
    ++counters_.steps_accepted;
    return StepStatus::kOk;
  }

  void dense(double t, Vec& y_out) const override {
    hermite_dense(t, t_prev_, t_, y_prev_, f_prev_, y_, f_, y_out);
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override { return h_fixed_; }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }

 private:
  Method method_;
  double h_fixed_;             ///< nominal step [s]
  double t_ = 0.0;             ///< current time [s]
  double t_prev_ = 0.0;        ///< start of the last accepted step [s]
  double t_base_ = 0.0;        ///< time the step grid counts from [s]
  long steps_since_base_ = 0;  ///< steps taken on the current grid
  Vec y_, y_prev_, y_new_, y_tmp_;
  Vec f_, f_prev_, f_new_;  ///< f at t_, t_prev_ and the trial point
  Vec k2_, k3_, k4_;        ///< inner stages
  SolverCounters counters_;
};

}  // namespace

std::unique_ptr<Stepper> make_explicit_rk_stepper(const SolverOptions& options, int n) {
  return std::make_unique<ExplicitRkStepper>(options, n);
}

}  // namespace pronk::ode::detail
