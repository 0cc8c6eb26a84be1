// Internal bookkeeping shared by the optimizer drivers: every evaluation goes
// through an EvaluationTracker (budget, stop flag, time limit, observer,
// counters, best point), and derivatives come from a FiniteDifferences helper
// that caches points keyed on the exact bits of x so that nothing is
// evaluated twice when a library asks for f, g and their derivatives at the
// same point. Not part of the public interface.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "optimize/optimizer.hpp"
#include "optimize/problem.hpp"

namespace pronk::optimize::detail {

/// Replacement for a non-finite cost or constraint value (the evaluation is
/// then counted failed). Also what a library sees after the tracker refused.
inline constexpr double kLargeValue = 1e10;

/// Why the tracker refuses further evaluations.
enum class StopCause {
  kNone,
  kMaxEvaluations,  ///< the next batch would exceed options.max_evaluations
  kMaxTime,         ///< options.max_time elapsed
  kStopFlag,        ///< options.stop_flag was set
  kError,           ///< the Problem or the observer threw, or broke its contract
};

/// Appends `part` to a "; "-separated message (nothing for an empty part).
void append_message(std::string* message, const std::string& part);

class EvaluationTracker {
 public:
  EvaluationTracker(const Problem& problem, const OptimizerOptions& options,
                    EvaluationObserver* observer);

  /// Evaluates the batch (Problem::evaluate_batch, results in input order),
  /// sanitises each result (non-finite -> kLargeValue, failed), passes them to
  /// the observer in order, and updates counters and the best point. Returns
  /// false and evaluates nothing when the run must stop (see stop_cause()).
  /// Never throws.
  bool evaluate(const std::vector<std::vector<double>>& xs,
                const std::vector<const char*>& purposes, std::vector<ProblemEvaluation>* out);

  /// Checks the stop flag and the time limit; true when the run must stop.
  bool should_stop();
  bool stopped() const { return cause_ != StopCause::kNone; }
  StopCause stop_cause() const { return cause_; }
  const std::string& stop_message() const { return cause_message_; }
  /// Records an error (e.g. an exception caught in a library callback).
  void record_error(const std::string& why);

  /// The value an optimizer should minimise for this evaluation: its cost,
  /// but a failed evaluation never looks better than the worst successful
  /// cost seen so far (its cost is lifted to that level; a clamped
  /// non-finite cost becomes exactly that level).
  double optimizer_cost(const ProblemEvaluation& e) const;
  /// Whether x (exact bits) was evaluated and failed.
  bool failed_point(const std::vector<double>& x) const;

  long evaluations() const { return evaluations_; }
  long failed_evaluations() const { return failed_; }
  /// The best point so far (empty when no evaluation succeeded).
  const std::vector<double>& best_x() const { return best_x_; }
  double elapsed() const;
  /// Fills counters, best point and timings of the result.
  void fill(OptimizerResult* result) const;
  /// When the tracker stopped the run (budget, time, stop flag, error), that
  /// reason overrides the library's status; the cause is added to the message.
  void apply_stop_cause(OptimizerResult* result) const;
  /// A driver ended by an exception: records the cause, status kFailed.
  void fail(OptimizerResult* result, const std::string& cause);
  /// Fills the result (see fill); without any successful evaluation the run
  /// cannot be reported converged.
  void finish(OptimizerResult* result) const;

 private:
  void consider_best(long index, const std::vector<double>& x, const ProblemEvaluation& e);

  const Problem& problem_;
  const OptimizerOptions& options_;
  EvaluationObserver* observer_;
  int m_;
  std::chrono::steady_clock::time_point start_;
  StopCause cause_ = StopCause::kNone;
  std::string cause_message_;

  long evaluations_ = 0, failed_ = 0, gradient_ = 0, nonfinite_ = 0;
  double evaluation_time_ = 0.0;
  bool any_ok_ = false;
  double highest_ok_cost_ = 0.0;
  std::vector<std::vector<double>> failed_points_;

  bool have_best_ = false, best_feasible_ = false;
  double best_violation_ = 0.0;
  long best_index_ = -1;
  std::vector<double> best_x_;
  ProblemEvaluation best_;
};

/// One evaluated point, with derivatives once they were asked for.
struct PointRecord {
  std::vector<double> x;
  ProblemEvaluation eval;
  bool has_derivatives = false;
  bool derivatives_ok = false;   ///< every difference used a successful evaluation
  std::vector<double> gradient;  ///< d value / dx_j (n)
  std::vector<double> jacobian;  ///< d g_i / dx_j, row-major (m x n)
};

/// Finite-difference derivatives over a tracker, with a small cache of the
/// most recent points (keyed on the exact bits of x). The scalar being
/// differenced is `value(evaluation)` (the optimizer's cost, possibly with a
/// penalty); constraints are differenced as they are.
class FiniteDifferences {
 public:
  using ValueFunction = std::function<double(const ProblemEvaluation&)>;
  FiniteDifferences(EvaluationTracker& tracker, const Problem& problem,
                    const OptimizerOptions& options, ValueFunction value);

  /// The evaluation at x ("objective"); nullptr when the tracker refused.
  std::shared_ptr<const PointRecord> point(const double* x);
  /// The evaluation and derivatives at x (stencil points are "gradient"
  /// evaluations, one batch, plus one batch of mirrored points replacing
  /// failed ones); nullptr when the tracker refused.
  std::shared_ptr<const PointRecord> derivatives(const double* x);

  /// The scalar value this helper differences.
  double value(const ProblemEvaluation& e) const { return value_(e); }

 private:
  std::shared_ptr<PointRecord> find(const double* x);
  std::shared_ptr<PointRecord> insert(const double* x, ProblemEvaluation e);

  /// A variable's stencil points: indices into the batch (-1: none) and exact offsets x' - x_j.
  struct StencilPlan {
    int first = -1, second = -1;
    double d_first = 0.0, d_second = 0.0;
  };
  struct Stencil {
    std::vector<StencilPlan> plan;  ///< per variable
    std::vector<std::vector<double>> batch;
    std::vector<const char*> purposes;
  };
  /// The stencil around x0 (with x0 itself first when with_center).
  Stencil plan_stencil(const std::vector<double>& x0, bool with_center) const;
  /// Evaluates the mirror images of failed one-sided points that lie inside the bounds;
  /// false when the tracker refused.
  bool evaluate_mirrors(const std::vector<double>& x0, const std::vector<StencilPlan>& plan,
                        const std::vector<ProblemEvaluation>& out,
                        std::vector<std::pair<int, double>>* mirror_of,
                        std::vector<ProblemEvaluation>* mirror_out);
  /// The gradient and Jacobian of rec from the stencil's evaluations.
  void difference(PointRecord* rec, const std::vector<StencilPlan>& plan,
                  const std::vector<ProblemEvaluation>& out,
                  const std::vector<std::pair<int, double>>& mirror_of,
                  const std::vector<ProblemEvaluation>& mirror_out) const;

  EvaluationTracker& tracker_;
  const OptimizerOptions& options_;
  ValueFunction value_;
  int n_, m_;
  std::vector<double> lower_, upper_;
  std::deque<std::shared_ptr<PointRecord>> cache_;
};

}  // namespace pronk::optimize::detail
