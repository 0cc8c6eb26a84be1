#include <cmath>
#include <sstream>
#include <string>

#include "optimize/ipopt_driver.hpp"
#include "optimize/nlopt_driver.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/pagmo_driver.hpp"

namespace pronk::optimize {

namespace {

/// Checks the Problem's contract before any library sees it; "" when fine.
std::string check_problem(const Problem& problem) {
  const int n = problem.dimension(), m = problem.num_constraints();
  if (n < 1) return "problem: dimension " + std::to_string(n) + " (must be >= 1)";
  if (m < 0) return "problem: " + std::to_string(m) + " constraints (must be >= 0)";
  const auto lo = problem.lower_bounds(), hi = problem.upper_bounds(), x0 = problem.initial_point();
  const auto un = static_cast<std::size_t>(n);
  if (lo.size() != un || hi.size() != un || x0.size() != un)
    return "problem: bounds/initial point sizes do not match the dimension " + std::to_string(n);
  const auto names = problem.variable_names();
  for (std::size_t j = 0; j < un; ++j) {
    const std::string name =
        j < names.size() ? names[j] : std::string(1, 'x').append(std::to_string(j));
    std::ostringstream s;
    if (std::isnan(lo[j]) || std::isnan(hi[j]) || lo[j] > hi[j]) {
      s << "problem: variable " << name << ": bounds [" << lo[j] << ", " << hi[j] << "] invalid";
      return s.str();
    }
    if (!std::isfinite(x0[j]) || x0[j] < lo[j] || x0[j] > hi[j]) {
      s << "problem: variable " << name << ": initial value " << x0[j] << " outside [" << lo[j]
        << ", " << hi[j] << "]";
      return s.str();
    }
  }
  return "";
}

}  // namespace

OptimizerResult run_optimizer(const Problem& problem, const OptimizerOptions& options,
                              EvaluationObserver* observer) {
  OptimizerResult result;
  result.library = options.library;
  result.algorithm = options.algorithm;
  std::string error;
  try {
    if (!options.validate(&error)) {
      result.message = "invalid optimizer options: " + error;
      return result;
    }
    error = check_problem(problem);
    if (!error.empty()) {
      result.message = error;
      return result;
    }
  } catch (const std::exception& e) {
    result.message = std::string("problem description failed: ") + e.what();
    return result;
  }
  if (options.library == "ipopt") return run_ipopt(problem, options, observer);
  if (options.library == "pagmo") return run_pagmo(problem, options, observer);
  return run_nlopt(problem, options, observer);
}

}  // namespace pronk::optimize
