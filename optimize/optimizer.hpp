// Optimizer drivers behind one options type and one result type.
#pragma once

#include <atomic>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/problem.hpp"

namespace pronk::optimize {

/// How to optimize. Validated when a study is loaded.
struct OptimizerOptions {
  std::string library = "nlopt";  ///< "nlopt", "ipopt" or "pagmo"
  std::string algorithm =
      "LN_BOBYQA";  ///< NLopt algorithm name (e.g. "LN_COBYLA", "GN_ISRES", "G_MLSL_LDS"),
                    ///< or a pagmo one ("cmaes", "xnes", "de", "sade", "de1220", "pso_gen")
  std::string local_algorithm = "LN_BOBYQA";  ///< local optimizer for multistart (MLSL) / AUGLAG
  long max_evaluations = 200;   ///< objective evaluations (incl. finite-difference points)
  double max_time = 0.0;        ///< wall-clock limit [s]; 0 = none
  double ftol_rel = 1e-6;       ///< relative cost tolerance (0 = off)
  double xtol_rel = 1e-6;       ///< relative variable tolerance (0 = off)
  unsigned long long seed = 1;  ///< seeds every random choice of the driver
  /// Weight of the quadratic penalty sum(max(g_j, 0)^2) added to the cost for
  /// algorithms without constraint support (reported as such in the result).
  double penalty_weight = 1e3;
  /// Ipopt options passed through (string, integer or number values).
  nlohmann::json ipopt_options = nlohmann::json::object();
  /// pagmo options: population, generations, ftol, xtol and the algorithm's own
  /// (optimize/pagmo_driver.hpp).
  nlohmann::json pagmo_options = nlohmann::json::object();
  /// Relative finite-difference step for gradient-based drivers. Per
  /// variable: step_j = fd_step * (upper_j - lower_j) when both bounds are
  /// finite, else fd_step * max(1, |x_j|); one-sided inward at a bound.
  double fd_step = 1e-6;
  /// Finite-difference scheme: "central" (2n extra evaluations per gradient,
  /// error O(h^2)) or "forward" (n, error O(h): cheaper, but gradient-based
  /// optimizers then often stall short of tight tolerances).
  std::string fd_scheme = "central";
  /// An evaluation is feasible when ok and every g_j(x) <= feasibility_tolerance.
  double feasibility_tolerance = 1e-8;
  /// Set asynchronously (Ctrl-C): the driver stops at the next evaluation and
  /// returns its best point with status kStopped.
  const std::atomic<bool>* stop_flag = nullptr;

  /// Checks every field; on failure writes "field: value: rule" into *error.
  bool validate(std::string* error) const;
};

enum class OptimizerStatus {
  kConverged,  ///< a tolerance was met
  kMaxEvaluations,
  kMaxTime,
  kStopped,  ///< stop_flag or a user stop
  kFailed,   ///< the library failed (message says why)
};
std::string_view to_string(OptimizerStatus s);

/// What happened (Ceres' Summary): the same for every driver.
struct OptimizerResult {
  OptimizerStatus status = OptimizerStatus::kFailed;
  std::string message;  ///< the library's own status text and any recorded cause
  std::string library, algorithm;
  bool constraints_as_penalty = false;  ///< the algorithm had no constraint support
  long evaluations = 0;                 ///< total evaluations made
  long failed_evaluations = 0;          ///< evaluations with ok == false
  long gradient_evaluations = 0;        ///< of which finite-difference points ("gradient")
  long nonfinite_evaluations = 0;  ///< evaluations with a NaN/inf value (clamped, counted failed)
  std::string library_status;      ///< the library's raw status ("XTOL_REACHED", "Solve_Succeeded")
  /// Best feasible point (or least infeasible if none); only ever a point
  /// that evaluated ok; empty (best_index -1) when no evaluation succeeded.
  std::vector<double> best_x;
  double best_cost = 0.0;
  std::vector<double> best_constraints;
  bool best_feasible = false;
  long best_index = -1;          ///< evaluation index of best_x
  double wall_time = 0.0;        ///< [s]
  double evaluation_time = 0.0;  ///< [s] spent inside Problem::evaluate*

  std::string brief_report() const;
  std::string full_report(const Problem& problem) const;
};

/// Runs the optimizer named by options.library. Never throws for numerical
/// trouble: evaluation failures and library errors end up in the result.
OptimizerResult run_optimizer(const Problem& problem, const OptimizerOptions& options,
                              EvaluationObserver* observer = nullptr);

}  // namespace pronk::optimize
