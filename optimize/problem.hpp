// The solver-independent optimization problem that every driver (NLopt,
// Ipopt) sees: n bounded variables, one cost, m inequality constraints
// g_j(x) <= 0. Drivers are thin adapters over it (TOWR/ifopt style).
#pragma once

#include <atomic>
#include <string>
#include <vector>

namespace pronk::optimize {

/// One evaluation as a driver sees it. A failed evaluation (ok == false) still
/// carries finite numbers (a penalty cost, violated constraints), never NaN.
struct ProblemEvaluation {
  bool ok = true;
  double cost = 0.0;
  std::vector<double> constraints;  ///< g_j(x); feasible when all <= 0
  std::string failure;              ///< why, when !ok
};

class Problem {
 public:
  virtual ~Problem() = default;
  virtual int dimension() const = 0;
  virtual int num_constraints() const = 0;
  virtual std::vector<double> lower_bounds() const = 0;
  virtual std::vector<double> upper_bounds() const = 0;
  /// Starting point, inside the bounds.
  virtual std::vector<double> initial_point() const = 0;
  virtual std::vector<std::string> variable_names() const = 0;
  virtual std::vector<std::string> constraint_names() const = 0;
  /// Thread-safe and deterministic; never throws (failures are data).
  virtual ProblemEvaluation evaluate(const std::vector<double>& x) const = 0;
  /// Evaluates several points (a driver's finite-difference stencil, a
  /// population); the default is serial, implementations may run them in
  /// parallel. Results are in input order whatever the thread count.
  virtual std::vector<ProblemEvaluation> evaluate_batch(
      const std::vector<std::vector<double>>& xs) const {
    std::vector<ProblemEvaluation> out;
    out.reserve(xs.size());
    for (const auto& x : xs) out.push_back(evaluate(x));
    return out;
  }
};

/// Sees every evaluation a driver makes, in the order the driver consumes them
/// (the study journal). `purpose` is "objective" or "gradient" (a finite-difference point).
class EvaluationObserver {
 public:
  virtual ~EvaluationObserver() = default;
  virtual void on_evaluation(long index, const std::vector<double>& x, const ProblemEvaluation& e,
                             const char* purpose) = 0;
};

}  // namespace pronk::optimize
