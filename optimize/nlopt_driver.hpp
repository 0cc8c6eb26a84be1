// NLopt driver: any NLopt algorithm by name over a Problem.
#pragma once

#include <string>

#include "optimize/optimizer.hpp"
#include "optimize/problem.hpp"

namespace pronk::optimize {

/// True when `name` is an NLopt algorithm name ("LN_BOBYQA", "GD_STOGO", ...).
bool is_nlopt_algorithm(const std::string& name);

/// Whether the algorithm takes nonlinear inequality constraints itself
/// (COBYLA, ISRES, MMA, CCSAQ, SLSQP, the AUGLAG family, ORIG_DIRECT, AGS);
/// other algorithms see a quadratic penalty instead.
bool nlopt_supports_inequality_constraints(const std::string& name);

/// Whether the algorithm needs a local optimizer (AUGLAG, AUGLAG_EQ, G_MLSL,
/// G_MLSL_LDS): options.local_algorithm is used for it.
bool nlopt_needs_local_algorithm(const std::string& name);

/// Runs options.algorithm (NLopt 2.7, nlopt_cxx build). Derivative-based
/// algorithms (LD_*, GD_*, or a local LD_* algorithm) get finite-difference
/// gradients through Problem::evaluate_batch. Seeded with options.seed before
/// the run (nlopt::srand). Never throws.
OptimizerResult run_nlopt(const Problem& problem, const OptimizerOptions& options,
                          EvaluationObserver* observer);

}  // namespace pronk::optimize
