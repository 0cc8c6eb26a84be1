// pagmo2 driver: population-based global optimizers (CMA-ES, xNES, DE, SADE,
// DE1220, generational PSO) over a Problem, each population evaluated as one
// batch (Problem::evaluate_batch: threads or MPI ranks).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/optimizer.hpp"
#include "optimize/problem.hpp"

namespace pronk::optimize {

/// True when `name` is a pagmo algorithm pronk offers ("cmaes", "xnes", "de", "sade",
/// "de1220", "pso_gen").
bool is_pagmo_algorithm(const std::string& name);

/// Checks the "options" of a pagmo study: population, generations, ftol, xtol and the
/// algorithm's own options (an unknown one is an error), the population against what
/// the algorithm needs and against max_evaluations. On failure writes "field: value:
/// rule" into *error, field "algorithm" or "options/NAME".
bool validate_pagmo_options(const std::string& algorithm, const nlohmann::json& options,
                            long max_evaluations, std::string* error);

/// Runs options.algorithm (pagmo 2.18) on the problem. The first population is the
/// initial point and population - 1 points drawn uniformly in the bounds (seeded by
/// options.seed); every later generation is evaluated as one batch, in the order pagmo
/// asks for its points, so the evaluations, the journal and the result are the same
/// whatever the thread or rank count. Constraints become the quadratic penalty
/// options.penalty_weight * sum(max(g_j, 0)^2) (result.constraints_as_penalty). Stops
/// at max_evaluations (whole generations), the generation cap, ftol/xtol (converged),
/// max_time or the stop flag. Bounds must be finite. Never throws.
OptimizerResult run_pagmo(const Problem& problem, const OptimizerOptions& options,
                          EvaluationObserver* observer);

}  // namespace pronk::optimize
