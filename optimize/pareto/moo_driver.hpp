// Multi-objective optimization over a batch function: pagmo's NSGA-II, MOEA/D or NSPSO
// (moo_options.hpp) minimizing a vector of objectives over a box, generation by generation,
// recording each generation's population, the non-dominated set of everything evaluated so
// far and its hypervolume against a reference point fixed for the run. Numerics only: the
// function never sees physics, and the caller decides how a batch runs (threads, MPI ranks).
//
// Evaluation. The first population is pagmo's (uniform in the box from the seed) and is one
// batch. nsga2 and nspso then evaluate each generation's new points as one batch through
// pagmo's batch evaluator (set_bfe). moead cannot: pagmo's MOEA/D-DE is steady-state, each
// offspring's parents are drawn from the population as the previous offspring of the same
// generation left it (an offspring replaces members only when its values are better), so
// offspring k + 1 is not known before offspring k is evaluated. No replay or dry run can put
// a generation into one batch without changing the algorithm; moead therefore evaluates one
// point per batch call, in pagmo's order (population calls per generation). Either way the
// outcome depends only on the seed and the function's values, never on threads or timing.
//
// Resume. Given the evaluations an earlier run made (in order), run() answers the points it
// asks for from that record, as long as it lasts and after checking each point is the same to
// the bit, and calls the batch function only for the rest: the rerun of an interrupted run
// reaches the same state bit for bit.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "optimize/pareto/front.hpp"
#include "optimize/pareto/moo_options.hpp"
#include "optimize/sensitivity/batch_function.hpp"

namespace pronk::optimize::pareto {

// The batch function of the sensitivity numerics fits as it is: a batch of points in, one
// vector of outputs per point out (here the objectives, all minimized, finite).
using Point = sensitivity::Point;
using BatchFunction = sensitivity::BatchFunction;

/// One evaluation of the run: the point and its objectives.
struct MooEvaluation {
  Point x;
  Objectives f;
};

/// The state after one generation.
struct MooGeneration {
  long index = 0;        ///< 0: the first population; g: after g generations
  long evaluations = 0;  ///< evaluations of the run so far
  std::vector<Point> x;  ///< the algorithm's population (nspso: the swarm's current positions)
  std::vector<Objectives> f;
  /// The non-dominated points among every evaluation so far (extend_front in front.hpp):
  /// indices into the run's evaluations, ascending.
  std::vector<std::size_t> front;
  double hypervolume = 0.0;  ///< of `front` against the run's reference point
};

/// Called after every generation (the first population included) with the generation and
/// the run's evaluations so far.
using MooObserver =
    std::function<void(const MooGeneration& generation, const std::vector<MooEvaluation>& all)>;

struct MooResult {
  Objectives reference;                    ///< the hypervolume reference point of the run
  std::vector<MooGeneration> generations;  ///< [0] the first population, then one per generation
  std::vector<double> hypervolumes;        ///< generations[g].hypervolume, per generation
  std::vector<MooEvaluation> evaluations;  ///< every evaluation, in order
  std::vector<Point> front_x;              ///< the final non-dominated set
  std::vector<Objectives> front_f;
  long knee = -1;             ///< knee() of the final front, an index into front_x
  long batch_calls = 0;       ///< calls of the batch function
  long recorded_answers = 0;  ///< evaluations answered from the record
};

/// Minimizes the `objectives` outputs of f over the box [lower, upper] (finite, lower < upper
/// everywhere). Throws std::invalid_argument for invalid options ("invalid options: " and
/// validate()'s messages), bounds, a batch answer of the wrong size or with a non-finite value
/// (report a failed evaluation as a large finite penalty), or a record that does not match.
MooResult run(const BatchFunction& f, const std::vector<double>& lower,
              const std::vector<double>& upper, long objectives, const MooOptions& options,
              const MooObserver& observer = nullptr,
              const std::vector<MooEvaluation>& recorded = {});

}  // namespace pronk::optimize::pareto
