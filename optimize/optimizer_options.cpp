#include <cmath>
#include <sstream>
#include <string>

#include "optimize/ipopt_driver.hpp"
#include "optimize/nlopt_driver.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/pagmo_driver.hpp"

namespace pronk::optimize {

namespace {

template <class T>
std::string text(const T& v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

bool fail(std::string* error, const std::string& field, const std::string& value,
          const std::string& rule) {
  if (error != nullptr) *error = field + ": " + value + ": " + rule;
  return false;
}

}  // namespace

std::string_view to_string(OptimizerStatus s) {
  switch (s) {
    case OptimizerStatus::kConverged:
      return "converged";
    case OptimizerStatus::kMaxEvaluations:
      return "max_evaluations";
    case OptimizerStatus::kMaxTime:
      return "max_time";
    case OptimizerStatus::kStopped:
      return "stopped";
    case OptimizerStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

bool OptimizerOptions::validate(std::string* error) const {
  if (library != "nlopt" && library != "ipopt" && library != "pagmo")
    return fail(error, "library", library, "expected \"nlopt\", \"ipopt\" or \"pagmo\"");
  if (library == "nlopt") {
    if (!is_nlopt_algorithm(algorithm))
      return fail(error, "algorithm", algorithm,
                  "not an NLopt algorithm name (e.g. LN_BOBYQA, LN_COBYLA, LN_NELDERMEAD, "
                  "LN_SBPLX, GN_CRS2_LM, GN_ISRES, GN_DIRECT_L, GD_STOGO, G_MLSL_LDS, AUGLAG)");
    if (nlopt_needs_local_algorithm(algorithm) && !is_nlopt_algorithm(local_algorithm))
      return fail(error, "local_algorithm", local_algorithm,
                  "not an NLopt algorithm name (e.g. LN_BOBYQA, LN_COBYLA)");
    if (nlopt_needs_local_algorithm(algorithm) &&
        (local_algorithm.rfind("LN_", 0) != 0 && local_algorithm.rfind("LD_", 0) != 0))
      return fail(error, "local_algorithm", local_algorithm,
                  "must be a local algorithm (LN_* or LD_*)");
  }
  if (max_evaluations < 1)
    return fail(error, "max_evaluations", text(max_evaluations), "must be >= 1");
  if (!std::isfinite(max_time) || max_time < 0.0)
    return fail(error, "max_time", text(max_time), "must be >= 0 s (0 = no limit)");
  if (!std::isfinite(ftol_rel) || ftol_rel < 0.0)
    return fail(error, "ftol_rel", text(ftol_rel), "must be >= 0 (0 = off)");
  if (!std::isfinite(xtol_rel) || xtol_rel < 0.0)
    return fail(error, "xtol_rel", text(xtol_rel), "must be >= 0 (0 = off)");
  if (!std::isfinite(penalty_weight) || penalty_weight <= 0.0)
    return fail(error, "penalty_weight", text(penalty_weight), "must be > 0");
  if (!std::isfinite(fd_step) || fd_step <= 0.0 || fd_step > 0.1)
    return fail(error, "fd_step", text(fd_step), "must be in (0, 0.1]");
  if (fd_scheme != "forward" && fd_scheme != "central")
    return fail(error, "fd_scheme", fd_scheme, "expected \"forward\" or \"central\"");
  if (!std::isfinite(feasibility_tolerance) || feasibility_tolerance < 0.0)
    return fail(error, "feasibility_tolerance", text(feasibility_tolerance), "must be >= 0");
  if (!ipopt_options.is_object())
    return fail(error, "ipopt_options", ipopt_options.dump(), "expected an object");
  if (library == "ipopt" && !validate_ipopt_options(ipopt_options, error)) return false;
  if (library == "pagmo" &&
      !validate_pagmo_options(algorithm, pagmo_options, max_evaluations, error))
    return false;
  return true;
}

}  // namespace pronk::optimize
