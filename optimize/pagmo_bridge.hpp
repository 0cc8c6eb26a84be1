// The bridge between pagmo and a pronk Problem: pagmo's user-defined problem (UDP)
// and batch evaluator (UDBFE) both answer through one PagmoBridge, which
// evaluates through the driver's EvaluationTracker (budget, journal, best point)
// in batches, so that a generation's points run in parallel over threads or MPI
// ranks (Problem::evaluate_batch) and are recorded in input order.
//
// Algorithms that evaluate point by point inside pagmo (cmaes, xnes, de, sade,
// de1220) run one generation at a time as a "generation replay": the generation
// is first run on copies of the algorithm and population in a dry run, in which
// every point pagmo asks for is recorded and answered with +inf; the recorded
// points are evaluated as one batch; the generation is run again on fresh copies,
// answered from those results, and repeated until a run asks for no point that
// was not evaluated, which is then kept. When the points of a generation depend
// only on its starting state (pagmo_independent_generation) that takes one batch;
// otherwise the driver evaluates one new point per replay. Either way the
// outcome depends only on the evaluation results, never on timing.
//
// Internal to the pagmo driver. Written so that several objectives fit later
// (fitness vectors of nobj entries; NSGA-II evaluates through the batch evaluator).
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <pagmo/problem.hpp>
#include <pagmo/types.hpp>

#include "optimize/evaluation_tracker.hpp"

namespace pronk::optimize::detail {

/// Thrown out of pagmo's evolve() when the tracker refuses further evaluations
/// (budget, time limit, stop flag, error); the driver catches it.
struct PagmoStop {};

class PagmoBridge {
 public:
  /// `penalty_weight` > 0 adds penalty_weight * sum(max(g_j, 0)^2) to the cost (pagmo's
  /// algorithms take no nonlinear constraints).
  PagmoBridge(EvaluationTracker& tracker, const Problem& problem, double penalty_weight);

  /// Evaluates the points as one tracker batch and returns their fitness values (also
  /// kept as this generation's answers); false when the tracker refused.
  bool evaluate(const std::vector<std::vector<double>>& xs, std::vector<double>* values);
  /// The value pagmo minimises for an evaluation: the tracker's optimizer cost (a failed
  /// evaluation never looks better than the worst successful one) plus the penalty.
  double fitness_value(const ProblemEvaluation& e) const;

  /// pagmo's fitness call: an answer of this generation; in a dry run, +inf for a point
  /// not evaluated yet (recorded in pending()); otherwise the point is evaluated alone
  /// (PagmoStop when refused).
  double fitness(const std::vector<double>& x);

  // Generation replay (see the file comment).
  void begin_generation();  ///< forgets the previous generation's answers
  void begin_dry_run();     ///< clears pending(), answers +inf for new points
  void end_dry_run();
  const std::vector<std::vector<double>>& pending() const { return pending_; }
  /// Answers this generation's committed run did not use (evaluated for nothing).
  long unused_answers() const;

  const std::vector<double>& lower() const { return lower_; }
  const std::vector<double>& upper() const { return upper_; }

 private:
  using Key = std::vector<std::uint64_t>;  ///< the exact bits of a point
  static Key key_of(const std::vector<double>& x);

  EvaluationTracker& tracker_;
  double penalty_weight_;
  std::vector<double> lower_, upper_;
  bool dry_run_ = false;
  std::map<Key, double> answers_;  ///< this generation's evaluated points
  std::set<Key> used_;             ///< answers asked for since the last dry run began
  std::vector<std::vector<double>> pending_;
};

/// pagmo's user-defined problem: bounds and fitness from a PagmoBridge, one objective,
/// no constraints (they are in the penalty). Default-constructible as pagmo requires.
class PagmoProblem {
 public:
  PagmoProblem() = default;
  explicit PagmoProblem(PagmoBridge* bridge) : bridge_(bridge) {}
  pagmo::vector_double fitness(const pagmo::vector_double& x) const;
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const;
  std::string get_name() const { return "pronk problem"; }

 private:
  PagmoBridge* bridge_ = nullptr;
};

/// pagmo's user-defined batch evaluator: the decision vectors pagmo hands over,
/// evaluated as one tracker batch (PagmoStop when refused).
class PagmoBatchEvaluator {
 public:
  PagmoBatchEvaluator() = default;
  explicit PagmoBatchEvaluator(PagmoBridge* bridge) : bridge_(bridge) {}
  pagmo::vector_double operator()(const pagmo::problem& p, const pagmo::vector_double& dvs) const;
  std::string get_name() const { return "pronk batch evaluator"; }

 private:
  PagmoBridge* bridge_ = nullptr;
};

}  // namespace pronk::optimize::detail
