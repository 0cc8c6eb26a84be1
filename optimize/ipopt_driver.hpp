// Ipopt 3.11 driver: interior point with a limited-memory Hessian and
// finite-difference derivatives over a Problem.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "optimize/optimizer.hpp"
#include "optimize/problem.hpp"

namespace pronk::optimize {

/// Checks Ipopt pass-through options: an object whose keys are Ipopt option
/// names and whose values have the option's type (string; integer; number,
/// an integer JSON value is accepted for a number option). Unknown names and
/// values Ipopt rejects are errors ("ipopt_options/NAME: VALUE: rule").
/// `hessian_approximation` cannot be "exact" (there is no Hessian).
bool validate_ipopt_options(const nlohmann::json& options, std::string* error);

/// Runs Ipopt on the problem: bounds, g(x) <= 0, gradient and dense
/// constraint Jacobian by finite differences (one evaluate_batch per
/// stencil), `hessian_approximation = limited-memory`, options passed
/// through, no ./ipopt.opt read, silent unless print_level is given. One
/// Ipopt solve per process at a time (MUMPS is not thread-safe). Never throws.
OptimizerResult run_ipopt(const Problem& problem, const OptimizerOptions& options,
                          EvaluationObserver* observer);

}  // namespace pronk::optimize
