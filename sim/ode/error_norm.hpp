// The error norm of the adaptive steppers: a step's local error estimate as one number.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "sim/ode/ode_system.hpp"

namespace pronk::ode {

/// How dopri5, rodas4 and radau5 measure the local error estimate `err` of a step from y0
/// to y1; a step is accepted when the result is at most 1 (radau5: below 1).
///
/// The norm belongs to the run, not to the system or the options: make_stepper() takes it
/// and the stepper keeps it over every reset(). A run builds it once from its model (the
/// mechanism's mass scale or its body norm, sim/pseudorigid/solver_norm.hpp), so the
/// system keeps only its dynamics, and SolverOptions stays a plain value read from JSON.
///
/// - plain (default): the RMS of err_i / (atol + rtol max(|y0_i|, |y1_i|)).
/// - scaled: the same with atol multiplied per state by atol_scale_i.
/// - custom: a system-specific norm (a mechanism's body norm), called with the stepper's
///   tolerances (radau5's transformed ones).
class ErrorNorm {
 public:
  /// err, y0, y1, rtol, atol -> the norm.
  using Custom =
      std::function<double(const Vec& err, const Vec& y0, const Vec& y1, double rtol, double atol)>;

  ErrorNorm() = default;
  /// The plain norm with atol x atol_scale_i for state i (atol_scale sized to the system).
  static ErrorNorm scaled(Vec atol_scale) {
    ErrorNorm n;
    n.scale_ = std::move(atol_scale);
    return n;
  }
  /// A norm of the system's own. `norm` must outlive the stepper's use of it.
  static ErrorNorm custom(Custom norm) {
    ErrorNorm n;
    n.custom_ = std::move(norm);
    return n;
  }

  /// True for the plain norm (no scale, no custom norm).
  bool is_plain() const { return !custom_ && scale_.size() == 0; }
  /// True for a custom norm (a system's own).
  bool is_custom() const { return static_cast<bool>(custom_); }
  /// The per-state atol multipliers of a scaled norm; empty for the plain and custom norms.
  const Vec& atol_scale() const { return scale_; }

  double operator()(const Vec& err, const Vec& y0, const Vec& y1, double rtol, double atol) const {
    if (custom_) return custom_(err, y0, y1, rtol, atol);
    const bool scaled = scale_.size() > 0;
    double sum = 0.0;
    const Eigen::Index n = err.size();
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = scaled ? atol * scale_[i] : atol;
      const double sk = a + rtol * std::max(std::abs(y0[i]), std::abs(y1[i]));
      const double q = err[i] / sk;
      sum += q * q;
    }
    return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  }

 private:
  Vec scale_;  ///< atol multiplier per state; empty: 1
  Custom custom_;
};

}  // namespace pronk::ode
