#include "optimize/pagmo_driver.hpp"

#include <pagmo/algorithm.hpp>
#include <pagmo/bfe.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/evaluation_tracker.hpp"
#include "optimize/pagmo_algorithms.hpp"
#include "optimize/pagmo_bridge.hpp"
#include "optimize/scenario.hpp"

namespace pronk::optimize {

namespace {

using detail::EvaluationTracker;
using detail::PagmoBridge;
using detail::PagmoSettings;
using detail::PagmoStop;

/// How the generations ended.
struct PagmoRun {
  long generations = 0;         ///< generations completed after the first population
  std::string converged;        ///< "ftol" or "xtol" when a tolerance was met
  bool generation_cap = false;  ///< the generation count ran out
  bool budget_cap = false;      ///< pso_gen: no further whole generation fits the budget
  long unused = 0;              ///< evaluations of replays that the kept run did not use
};

/// The first population: the initial point, then points uniform in the bounds
/// (SplitMix64 from the seed), evaluated as one batch. False when the tracker refused.
bool first_population(PagmoBridge& bridge, const Problem& problem, const PagmoSettings& s,
                      unsigned long long seed, pagmo::population* pop) {
  std::vector<std::vector<double>> xs = {problem.initial_point()};
  SplitMix64 g(mix_seed(seed, 1));
  const auto& lo = bridge.lower();
  const auto& hi = bridge.upper();
  while (static_cast<long>(xs.size()) < s.population) {
    std::vector<double> x(lo.size());
    for (std::size_t j = 0; j < x.size(); ++j) x[j] = std::min(hi[j], g.uniform(lo[j], hi[j]));
    xs.push_back(std::move(x));
  }
  std::vector<double> values;
  if (!bridge.evaluate(xs, &values)) return false;
  for (std::size_t i = 0; i < xs.size(); ++i) pop->push_back(xs[i], {values[i]});
  return true;
}

/// "xtol" or "ftol" when the population is that flat (pagmo DE's test: the best and the
/// worst individual), else "".
std::string tolerance_met(const pagmo::population& pop, const PagmoSettings& s) {
  const auto b = pop.best_idx(), w = pop.worst_idx();
  double dx = 0.0;
  for (std::size_t j = 0; j < pop.get_x()[b].size(); ++j)
    dx += std::abs(pop.get_x()[w][j] - pop.get_x()[b][j]);
  const double df = std::abs(pop.get_f()[w][0] - pop.get_f()[b][0]);
  if (s.xtol > 0.0 && dx < s.xtol) return "xtol";
  if (s.ftol > 0.0 && df < s.ftol) return "ftol";
  return "";
}

/// One generation by replay (pagmo_bridge.hpp): dry runs on copies until one asks for no
/// new point, which is kept. False when the tracker refused.
bool replay_generation(PagmoBridge& bridge, bool independent, pagmo::algorithm* algo,
                       pagmo::population* pop, long* unused) {
  bridge.begin_generation();
  for (;;) {
    bridge.begin_dry_run();
    pagmo::algorithm trial = *algo;
    pagmo::population next = trial.evolve(*pop);
    bridge.end_dry_run();
    if (bridge.pending().empty()) {
      *algo = std::move(trial);
      *pop = std::move(next);
      *unused += bridge.unused_answers();
      return true;
    }
    const std::vector<std::vector<double>> batch =
        independent ? bridge.pending() : std::vector<std::vector<double>>{bridge.pending().front()};
    std::vector<double> values;
    if (!bridge.evaluate(batch, &values)) return false;
  }
}

/// cmaes, xnes, de, sade, de1220: one evolve() per generation, with the algorithm's state
/// kept between calls.
void run_replayed(PagmoBridge& bridge, EvaluationTracker& tracker, const PagmoSettings& s,
                  unsigned seed, pagmo::population* pop, PagmoRun* run) {
  pagmo::algorithm algo = detail::make_pagmo_algorithm(s, 1u, seed, nullptr);
  const bool independent = detail::pagmo_independent_generation(s);
  for (;;) {
    if (s.generations > 0 && run->generations >= s.generations) {
      run->generation_cap = true;
      return;
    }
    if (tracker.should_stop() || !replay_generation(bridge, independent, &algo, pop, &run->unused))
      return;
    ++run->generations;
    run->converged = tolerance_met(*pop, s);
    if (!run->converged.empty()) return;
  }
}

/// pso_gen: one evolve() over every generation the budget holds, its swarm evaluated
/// through the batch evaluator.
void run_native(PagmoBridge& bridge, const PagmoSettings& s, long max_evaluations, unsigned seed,
                pagmo::population* pop, PagmoRun* run) {
  long generations = (max_evaluations - s.population) / s.population;
  run->budget_cap = true;
  if (s.generations > 0 && s.generations <= generations) {
    generations = s.generations;
    run->budget_cap = false;
    run->generation_cap = true;
  }
  const pagmo::bfe batch{detail::PagmoBatchEvaluator(&bridge)};
  pagmo::algorithm algo =
      detail::make_pagmo_algorithm(s, static_cast<unsigned>(generations), seed, &batch);
  *pop = algo.evolve(*pop);  // PagmoStop when the tracker refuses (time, stop flag)
}

std::string compact(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Status and message of a finished run: converged (a tolerance), the generation count,
/// the budget, or the tracker's stop cause (budget, time, stop flag, error).
void report(const PagmoSettings& s, const PagmoRun& run, const OptimizerOptions& options,
            const EvaluationTracker& tracker, OptimizerResult* result) {
  std::string text = "pagmo " + s.algorithm + ": population " + std::to_string(s.population) +
                     ", " + std::to_string(run.generations) + " generation(s) after the first";
  result->status = OptimizerStatus::kMaxEvaluations;
  result->library_status = "budget";
  if (!run.converged.empty()) {
    result->status = OptimizerStatus::kConverged;
    result->library_status = run.converged;
    text += ", population flatter than " + run.converged + " " +
            compact(run.converged == "xtol" ? s.xtol : s.ftol);
  } else if (run.generation_cap && !tracker.stopped()) {
    result->library_status = "generations";
    text += ", the generation count reached";
  } else if (run.budget_cap && !tracker.stopped()) {
    text += ", no further whole generation fits the evaluation budget of " +
            std::to_string(options.max_evaluations);
  } else if (tracker.stop_cause() != detail::StopCause::kMaxEvaluations) {
    result->library_status = "stopped";
  }
  result->message = text;
  tracker.apply_stop_cause(result);
  if (run.unused > 0)
    detail::append_message(
        &result->message,
        std::to_string(run.unused) + " evaluation(s) of generation replays unused by the kept run");
  if (result->constraints_as_penalty)
    detail::append_message(&result->message,
                           "constraints added to the cost as a quadratic penalty (weight " +
                               compact(options.penalty_weight) + ")");
}

}  // namespace

bool is_pagmo_algorithm(const std::string& name) {
  for (const auto& n : detail::pagmo_algorithm_names())
    if (n == name) return true;
  return false;
}

bool validate_pagmo_options(const std::string& algorithm, const nlohmann::json& options,
                            long max_evaluations, std::string* error) {
  PagmoSettings s;
  return detail::parse_pagmo_settings(algorithm, options, max_evaluations, &s, error);
}

OptimizerResult run_pagmo(const Problem& problem, const OptimizerOptions& options,
                          EvaluationObserver* observer) {
  OptimizerResult result;
  result.library = "pagmo";
  result.algorithm = options.algorithm;
  EvaluationTracker tracker(problem, options, observer);
  try {
    PagmoSettings s;
    std::string error;
    if (!detail::parse_pagmo_settings(options.algorithm, options.pagmo_options,
                                      options.max_evaluations, &s, &error))
      throw std::invalid_argument("invalid options: " + error);
    for (int j = 0; j < problem.dimension(); ++j) {
      const auto ju = static_cast<std::size_t>(j);
      if (!std::isfinite(problem.lower_bounds()[ju]) || !std::isfinite(problem.upper_bounds()[ju]))
        throw std::invalid_argument("pagmo's algorithms need finite bounds on every variable");
    }
    result.constraints_as_penalty = problem.num_constraints() > 0;
    PagmoBridge bridge(tracker, problem,
                       result.constraints_as_penalty ? options.penalty_weight : 0.0);
    const auto seed = static_cast<unsigned>(mix_seed(options.seed, 0) & 0xffffffffULL);
    pagmo::population pop{pagmo::problem{detail::PagmoProblem(&bridge)}, 0u, seed};
    PagmoRun run;
    try {
      if (first_population(bridge, problem, s, options.seed, &pop)) {
        if (detail::pagmo_native_batch(s)) {
          run_native(bridge, s, options.max_evaluations, seed, &pop, &run);
        } else {
          run_replayed(bridge, tracker, s, seed, &pop, &run);
        }
      }
    } catch (const PagmoStop&) {
      // The tracker refused an evaluation inside evolve(): its stop cause says why.
    }
    if (detail::pagmo_native_batch(s))
      run.generations = std::max(0L, tracker.evaluations() - s.population) / s.population;
    report(s, run, options, tracker, &result);
  } catch (const std::exception& e) {
    tracker.fail(&result, std::string("pagmo driver: ") + e.what());
  } catch (...) {
    tracker.fail(&result, "pagmo driver: non-standard exception");
  }
  tracker.finish(&result);
  return result;
}

}  // namespace pronk::optimize
