// The step-size control of the adaptive steppers (dopri5, rodas4, radau5): the adapted step,
// the trial step towards a limit, the new step from an error norm, and the accept/reject
// loop of the embedded methods.
#pragma once

#include <algorithm>
#include <cmath>

#include "sim/ode/solver.hpp"

namespace pronk::ode::detail {

/// Hairer's step-size controller: the step changes by h_new = h / quot with
/// quot = clamp(err^exponent / safety, quot_min, quot_max), optionally with Lund's PI
/// stabilisation (dopri5: err^exponent / err_prev^beta) or Gustafsson's predictive
/// controller (rodas4, radau5: quot = max(quot, (h_prev / h) (err^2 / err_prev)^exponent /
/// safety)). It owns the adapted step across reset()s of its stepper. The arithmetic is
/// written in each original code's order: results are bit-identical to them.
class StepSizeController {
 public:
  struct Params {
    double safety;            ///< safety factor on the proposed step
    double quot_min;          ///< smallest h / h_new (1 / the largest growth factor)
    double quot_max;          ///< largest h / h_new (1 / the largest reduction factor)
    double exponent;          ///< of the error: 1 / (order + 1), or the PI controller's
    double err_floor;         ///< the error is raised to at least this before the power
    double beta = 0.0;        ///< PI exponent of the previous accepted error (0: none)
    bool predictive = false;  ///< Gustafsson's predictive controller after accepted steps
  };

  /// One attempt: the adapted step h_adapted (<= h_max), and the step h to t_new actually
  /// tried (stretched or cut to end at t_limit when within 1 % of it).
  struct Trial {
    double h_adapted, h, t_new;
  };

  StepSizeController(const Params& p, const SolverOptions& o)
      : p_(p), h_max_(o.h_max), h_min_(o.h_min), h_initial_(o.h_initial) {}

  /// On the first reset(): the first trial step, options.h_initial (at most h_max) or,
  /// when that is 0, automatic(); later resets keep the adapted step.
  template <typename Automatic>
  void choose_initial(Automatic&& automatic) {
    if (chosen_) return;
    h_ = h_initial_ > 0.0 ? std::min(h_initial_, h_max_) : automatic();
    chosen_ = true;
  }

  double h() const { return h_; }
  double h_max() const { return h_max_; }
  double h_min() const { return h_min_; }

  /// The next attempt from t towards t_limit (> t).
  Trial trial(double t, double t_limit) const {
    const double h_adapted = std::min(h_, h_max_);
    double h = h_adapted;
    double t_new = t + h;
    if (t + 1.01 * h >= t_limit) {  // stretch or shorten to hit t_limit exactly
      h = t_limit - t;
      t_new = t_limit;
    }
    return {h_adapted, h, t_new};
  }

  /// Sets the step of the next attempt after a failed one; false when it is below h_min
  /// (a step-size collapse).
  bool retry(double h_next) {
    h_ = h_next;
    return !(h_ < h_min_);
  }

  /// h / h_new for a step h with error err and safety factor `safety`, without the PI and
  /// predictive terms (a rejected step's proposal).
  double quotient(double err, double safety) const {
    const double x = std::pow(std::max(err, p_.err_floor), p_.exponent);
    return std::clamp(x / safety, p_.quot_min, p_.quot_max);
  }

  /// The proposal after the accepted step h of error err (h / quot with the PI or the
  /// predictive term; `predict` false skips the latter); remembers h and err for the next.
  double accepted(double h, double err, double safety, bool predict = true) {
    double x = std::pow(std::max(err, p_.err_floor), p_.exponent);
    if (p_.beta > 0.0) x = x / std::pow(facold_, p_.beta);
    double quot = std::clamp(x / safety, p_.quot_min, p_.quot_max);
    double h_next = h / quot;
    if (p_.predictive) {
      if (predict && h_acc_ > 0.0) {
        double facgus = (h_acc_ / h) * std::pow(err * err / err_acc_, p_.exponent) / p_.safety;
        facgus = std::clamp(facgus, p_.quot_min, p_.quot_max);
        quot = std::max(quot, facgus);
        h_next = h / quot;
      }
      h_acc_ = h;
      err_acc_ = std::max(1e-2, err);
    }
    if (p_.beta > 0.0) facold_ = std::max(err, 1e-4);
    return h_next;
  }

  /// The proposal h_next after an accepted attempt at most h_max, and at most the step
  /// taken when a rejection preceded it.
  double bounded(double h_next, double h, bool rejected) const {
    h_next = std::min(h_next, h_max_);
    return rejected ? std::min(h_next, h) : h_next;
  }
  /// Sets the adapted step after an accepted attempt: h_next, but a step cut short to hit
  /// t_limit (without a rejection) says little about the right size and keeps h_adapted.
  void set_next(double h_next, const Trial& trial, bool rejected) {
    if (trial.h < trial.h_adapted && !rejected) h_next = std::max(h_next, trial.h_adapted);
    h_ = h_next;
  }

  /// One accepted step of an embedded explicit or Rosenbrock method from t towards t_limit
  /// (> t): attempt(h, t_new) tries a step and returns its error norm (non-finite on
  /// failure), commit(h, t_new) accepts it. Rejections shrink the step by the controller, a
  /// non-finite attempt by 10 (at most kMaxNonFinite in a row); both are counted.
  template <typename Attempt, typename Commit>
  StepStatus step(double t, double t_limit, SolverCounters& counters, Attempt&& attempt,
                  Commit&& commit) {
    bool rejected = false;
    int non_finite = 0;
    for (;;) {
      const Trial tr = trial(t, t_limit);
      if (!(tr.t_new > t)) return StepStatus::kStepSizeCollapse;  // h below time resolution
      const double err = attempt(tr.h, tr.t_new);
      if (!std::isfinite(err)) {
        ++counters.steps_rejected;
        if (++non_finite > kMaxNonFinite) return StepStatus::kNonFinite;
        rejected = true;
        if (!retry(tr.h * 0.1)) return StepStatus::kStepSizeCollapse;
        continue;
      }
      if (err <= 1.0) {
        set_next(bounded(accepted(tr.h, err, p_.safety), tr.h, rejected), tr, rejected);
        commit(tr.h, tr.t_new);
        return StepStatus::kOk;
      }
      ++counters.steps_rejected;
      rejected = true;
      if (!retry(tr.h / quotient(err, p_.safety))) return StepStatus::kStepSizeCollapse;
    }
  }

  /// Hairer's first guess of a step from the scales of y and f = y' (the start of hinit):
  /// 0.01 |y| / |f| in the weighted norm of atol + rtol |y_i|, 1e-6 s when either is tiny.
  /// *dnf (optional): the squared weighted norm of f.
  static double first_guess(const Vec& y, const Vec& f, double rtol, double atol,
                            double* dnf_out = nullptr) {
    const Eigen::Index n = y.size();
    double dnf = 0.0, dny = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double sk = atol + rtol * std::abs(y[i]);
      dnf += (f[i] / sk) * (f[i] / sk);
      dny += (y[i] / sk) * (y[i] / sk);
    }
    if (dnf_out != nullptr) *dnf_out = dnf;
    return (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
  }

  /// Non-finite attempts in a row before step() gives up.
  static constexpr int kMaxNonFinite = 8;

 private:
  Params p_;
  double h_max_, h_min_, h_initial_;  ///< step limits and first trial step [s]
  double h_ = 0.0;                    ///< the adapted step the next attempt tries [s]
  bool chosen_ = false;               ///< the first step is chosen (first reset done)
  double facold_ = 1e-4;              ///< previous accepted error (PI control)
  double h_acc_ = 0.0;                ///< previous accepted step (predictive control) [s]
  double err_acc_ = 1e-2;             ///< previous accepted error (predictive control)
};

}  // namespace pronk::ode::detail
