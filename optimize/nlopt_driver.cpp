#include "optimize/nlopt_driver.hpp"

#include <nlopt.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "optimize/evaluation_tracker.hpp"

namespace pronk::optimize {

namespace {

using detail::EvaluationTracker;
using detail::FiniteDifferences;
using detail::kLargeValue;
using detail::StopCause;

/// Owns an nlopt_opt.
struct OptDeleter {
  void operator()(nlopt_opt o) const { nlopt_destroy(o); }
};
using OptPtr = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, OptDeleter>;

/// The algorithm for a name, or -1: NLopt's own names (nlopt_algorithm_to_string).
/// nlopt_algorithm_from_string is not used: for an unknown name it returns -1 as an
/// nlopt_algorithm, a value outside the enum (undefined behaviour to load).
int algorithm_id(const std::string& name) {
  for (int id = 0; id < NLOPT_NUM_ALGORITHMS; ++id) {
    const char* n = nlopt_algorithm_to_string(static_cast<nlopt_algorithm>(id));
    if (n != nullptr && name == n) return id;
  }
  return -1;
}

double dummy_function(unsigned, const double*, double*, void*) { return 0.0; }

/// What the callbacks share.
struct Context {
  nlopt_opt opt = nullptr;
  EvaluationTracker* tracker = nullptr;
  FiniteDifferences* fd = nullptr;
  /// Values or derivatives handed to NLopt that came from failed evaluations.
  long tainted = 0;
};

void stop_now(Context& c) { nlopt_force_stop(c.opt); }

/// Restarts of a local algorithm to re-check a convergence claim (see run_nlopt).
constexpr int kMaxRestarts = 3;

double finite_or_large(double v) { return std::isfinite(v) ? v : kLargeValue; }

/// The objective NLopt sees. Never throws and never returns NaN: on any
/// trouble it records the cause and forces NLopt to stop.
double objective(unsigned n, const double* x, double* grad, void* data) {
  auto& c = *static_cast<Context*>(data);
  try {
    auto rec = grad != nullptr ? c.fd->derivatives(x) : c.fd->point(x);
    if (!rec) {
      stop_now(c);
      if (grad != nullptr) std::fill(grad, grad + n, 0.0);
      return kLargeValue;
    }
    if (!rec->eval.ok || (grad != nullptr && !rec->derivatives_ok)) ++c.tainted;
    if (grad != nullptr) {
      for (unsigned j = 0; j < n; ++j)
        grad[j] = std::isfinite(rec->gradient[j]) ? rec->gradient[j] : 0.0;
    }
    if (c.tracker->should_stop()) stop_now(c);
    return finite_or_large(c.fd->value(rec->eval));
  } catch (const std::exception& e) {
    c.tracker->record_error(std::string("exception in the NLopt objective: ") + e.what());
  } catch (...) {
    c.tracker->record_error("non-standard exception in the NLopt objective");
  }
  stop_now(c);
  if (grad != nullptr) std::fill(grad, grad + n, 0.0);
  return kLargeValue;
}

/// The inequality constraints g(x) <= 0 for algorithms that take them.
void constraints(unsigned m, double* result, unsigned n, const double* x, double* grad,
                 void* data) {
  auto& c = *static_cast<Context*>(data);
  try {
    auto rec = grad != nullptr ? c.fd->derivatives(x) : c.fd->point(x);
    if (rec) {
      if (!rec->eval.ok || (grad != nullptr && !rec->derivatives_ok)) ++c.tainted;
      for (unsigned i = 0; i < m; ++i) result[i] = finite_or_large(rec->eval.constraints[i]);
      if (grad != nullptr) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(m) * n; ++k)
          grad[k] = std::isfinite(rec->jacobian[k]) ? rec->jacobian[k] : 0.0;
      }
      if (c.tracker->should_stop()) stop_now(c);
      return;
    }
  } catch (const std::exception& e) {
    c.tracker->record_error(std::string("exception in the NLopt constraints: ") + e.what());
  } catch (...) {
    c.tracker->record_error("non-standard exception in the NLopt constraints");
  }
  stop_now(c);
  std::fill(result, result + m, kLargeValue);
  if (grad != nullptr) std::fill(grad, grad + static_cast<std::size_t>(m) * n, 0.0);
}

std::string result_text(nlopt_result r) {
  switch (r) {
    case NLOPT_FAILURE:
      return "FAILURE";
    case NLOPT_INVALID_ARGS:
      return "INVALID_ARGS";
    case NLOPT_OUT_OF_MEMORY:
      return "OUT_OF_MEMORY";
    case NLOPT_ROUNDOFF_LIMITED:
      return "ROUNDOFF_LIMITED";
    case NLOPT_FORCED_STOP:
      return "FORCED_STOP";
    case NLOPT_SUCCESS:
      return "SUCCESS";
    case NLOPT_STOPVAL_REACHED:
      return "STOPVAL_REACHED";
    case NLOPT_FTOL_REACHED:
      return "FTOL_REACHED";
    case NLOPT_XTOL_REACHED:
      return "XTOL_REACHED";
    case NLOPT_MAXEVAL_REACHED:
      return "MAXEVAL_REACHED";
    case NLOPT_MAXTIME_REACHED:
      return "MAXTIME_REACHED";
    default:
      return "result " + std::to_string(static_cast<int>(r));
  }
}

OptimizerStatus map_result(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS:
    case NLOPT_STOPVAL_REACHED:
    case NLOPT_FTOL_REACHED:
    case NLOPT_XTOL_REACHED:
    case NLOPT_ROUNDOFF_LIMITED:  // "typically still a useful result" (NLopt docs)
      return OptimizerStatus::kConverged;
    case NLOPT_MAXEVAL_REACHED:
      return OptimizerStatus::kMaxEvaluations;
    case NLOPT_MAXTIME_REACHED:
      return OptimizerStatus::kMaxTime;
    case NLOPT_FORCED_STOP:
      return OptimizerStatus::kStopped;
    default:
      return OptimizerStatus::kFailed;
  }
}

void append(std::string* message, const std::string& part) {
  detail::append_message(message, part);
}

/// Applies the stopping criteria shared by the main and the local optimizer.
void set_tolerances(nlopt_opt o, const OptimizerOptions& options) {
  nlopt_set_ftol_rel(o, options.ftol_rel);
  nlopt_set_xtol_rel(o, options.xtol_rel);
}

}  // namespace

bool is_nlopt_algorithm(const std::string& name) { return algorithm_id(name) >= 0; }

bool nlopt_supports_inequality_constraints(const std::string& name) {
  const int id = algorithm_id(name);
  if (id < 0) return false;
  // Ask NLopt itself: it rejects constraints for algorithms without support.
  OptPtr o(nlopt_create(static_cast<nlopt_algorithm>(id), 1));
  if (!o) return false;
  return nlopt_add_inequality_constraint(o.get(), &dummy_function, nullptr, 0.0) == NLOPT_SUCCESS;
}

bool nlopt_needs_local_algorithm(const std::string& name) {
  const int id = algorithm_id(name);
  return id == NLOPT_AUGLAG || id == NLOPT_AUGLAG_EQ || id == NLOPT_G_MLSL ||
         id == NLOPT_G_MLSL_LDS;
}

namespace {

/// The nonlinear constraints: NLopt's own when the algorithm takes them, else a penalty
/// (result->constraints_as_penalty). Returns an error message, or "".
std::string nlopt_add_constraints(nlopt_opt opt, int m, const OptimizerOptions& options,
                                  Context* ctx, OptimizerResult* result) {
  if (m <= 0) return "";
  const std::vector<double> tol(static_cast<std::size_t>(m), 0.0);
  if (nlopt_supports_inequality_constraints(options.algorithm)) {
    if (nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(m), &constraints, ctx,
                                         tol.data()) != NLOPT_SUCCESS) {
      return std::string("nlopt_add_inequality_mconstraint: ") + nlopt_get_errmsg(opt);
    }
  } else {
    result->constraints_as_penalty = true;
  }
  return "";
}

/// The local optimizer of AUGLAG and MLSL. Returns an error message, or "".
std::string nlopt_add_local_optimizer(nlopt_opt opt, int n, const OptimizerOptions& options,
                                      OptimizerResult* result) {
  if (!nlopt_needs_local_algorithm(options.algorithm)) return "";
  const int local_id = algorithm_id(options.local_algorithm);
  if (local_id < 0) return "unknown NLopt local algorithm '" + options.local_algorithm + "'";
  OptPtr local(nlopt_create(static_cast<nlopt_algorithm>(local_id), static_cast<unsigned>(n)));
  if (!local) return "nlopt_create failed for " + options.local_algorithm;
  set_tolerances(local.get(), options);
  if (nlopt_set_local_optimizer(opt, local.get()) != NLOPT_SUCCESS)
    return std::string("nlopt_set_local_optimizer: ") + nlopt_get_errmsg(opt);
  append(&result->message, "local algorithm " + options.local_algorithm);
  return "";
}

/// How nlopt_optimize ended, after the restarts that re-check a convergence claim.
struct NloptOutcome {
  nlopt_result r = NLOPT_FAILURE;
  int restarts = 0;
  long tainted_in_last_run = 0;
};

NloptOutcome nlopt_optimize_checked(nlopt_opt opt, int id, const OptimizerOptions& options,
                                    const EvaluationTracker& tracker, const Context& ctx,
                                    std::vector<double>* x) {
  NloptOutcome out;
  nlopt_srand(static_cast<unsigned long>(options.seed));  // reproducible random algorithms
  double minf = 0.0;
  long tainted_before = ctx.tainted;
  out.r = nlopt_optimize(opt, x->data(), &minf);
  // A failed evaluation reaches NLopt as a (lifted) high value, which can
  // corrupt a model (BOBYQA, a finite-difference gradient, ...) into
  // claiming convergence at a wrong point. A local algorithm's claim made
  // after NLopt used such values is re-checked by restarting from the best
  // successful point with the remaining budget; a claim is trusted only from
  // a run in which NLopt saw no value derived from a failed evaluation.
  const bool local = options.algorithm.rfind("LN_", 0) == 0 ||
                     options.algorithm.rfind("LD_", 0) == 0 || id == NLOPT_AUGLAG ||
                     id == NLOPT_AUGLAG_EQ;
  while (local && map_result(out.r) == OptimizerStatus::kConverged && !tracker.stopped() &&
         ctx.tainted > tainted_before && out.restarts < kMaxRestarts && !tracker.best_x().empty() &&
         tracker.evaluations() < options.max_evaluations) {
    ++out.restarts;
    tainted_before = ctx.tainted;
    *x = tracker.best_x();
    nlopt_set_maxeval(opt, static_cast<int>(std::min<long>(
                               options.max_evaluations - tracker.evaluations(), INT_MAX)));
    if (options.max_time > 0.0)
      nlopt_set_maxtime(opt, std::max(1e-3, options.max_time - tracker.elapsed()));
    out.r = nlopt_optimize(opt, x->data(), &minf);
  }
  out.tainted_in_last_run = ctx.tainted - tainted_before;
  return out;
}

/// The status and message of a finished run (x: where NLopt ended).
void nlopt_report(nlopt_opt opt, const NloptOutcome& out, const OptimizerOptions& options,
                  EvaluationTracker& tracker, const std::vector<double>& x,
                  OptimizerResult* result) {
  const nlopt_result r = out.r;
  result->library_status = result_text(r);
  std::string lib = "NLopt: " + result->library_status;
  if (r < 0 && r != NLOPT_FORCED_STOP) {
    const char* msg = nlopt_get_errmsg(opt);
    if (msg != nullptr && *msg != '\0') lib += std::string(" (") + msg + ")";
  }
  result->status = map_result(r);
  result->message = lib + (result->message.empty() ? "" : "; " + result->message);
  tracker.apply_stop_cause(result);
  if (r == NLOPT_FAILURE && tracker.stop_cause() == StopCause::kNone) {
    OptimizerResult counts;
    tracker.fill(&counts);
    if (counts.gradient_evaluations > 0)
      append(&result->message,
             "a gradient-based NLopt algorithm ending with FAILURE usually means the "
             "finite-difference gradient noise exceeds the tolerances (try fd_scheme "
             "\"central\", a larger fd_step or looser xtol_rel/ftol_rel)");
  }
  if (out.restarts > 0)
    append(&result->message, std::to_string(out.restarts) +
                                 " restart(s) from the best point to re-check a convergence "
                                 "claim made while evaluations failed");
  if (result->status == OptimizerStatus::kConverged && out.tainted_in_last_run > 0) {
    result->status = OptimizerStatus::kFailed;
    append(&result->message, "convergence not trusted: NLopt used " +
                                 std::to_string(out.tainted_in_last_run) +
                                 " value(s) or gradient(s) from failed evaluations during the "
                                 "final run (they can corrupt its model); the best successful "
                                 "point is reported");
  }
  if (result->status == OptimizerStatus::kConverged && tracker.failed_point(x)) {
    result->status = OptimizerStatus::kFailed;
    append(&result->message,
           "NLopt ended at a point whose evaluation failed; the best successful point is "
           "reported");
  }
  if (result->constraints_as_penalty) {
    append(&result->message, options.algorithm +
                                 " does not take nonlinear constraints: they were added to the "
                                 "cost as a quadratic penalty (weight " +
                                 std::to_string(options.penalty_weight) + ")");
  }
}

}  // namespace

OptimizerResult run_nlopt(const Problem& problem, const OptimizerOptions& options,
                          EvaluationObserver* observer) {
  OptimizerResult result;
  result.library = "nlopt";
  result.algorithm = options.algorithm;
  EvaluationTracker tracker(problem, options, observer);
  auto fail = [&](const std::string& why) {
    result.status = OptimizerStatus::kFailed;
    append(&result.message, why);
    tracker.fill(&result);
    return result;
  };
  try {
    const int id = algorithm_id(options.algorithm);
    if (id < 0) return fail("unknown NLopt algorithm '" + options.algorithm + "'");
    const int n = problem.dimension();
    const int m = problem.num_constraints();
    OptPtr opt(nlopt_create(static_cast<nlopt_algorithm>(id), static_cast<unsigned>(n)));
    if (!opt) return fail("nlopt_create failed for " + options.algorithm);

    const std::vector<double> lower = problem.lower_bounds(), upper = problem.upper_bounds();
    nlopt_set_lower_bounds(opt.get(), lower.data());
    nlopt_set_upper_bounds(opt.get(), upper.data());

    Context ctx;
    ctx.opt = opt.get();
    ctx.tracker = &tracker;
    if (nlopt_set_min_objective(opt.get(), &objective, &ctx) != NLOPT_SUCCESS)
      return fail(std::string("nlopt_set_min_objective: ") + nlopt_get_errmsg(opt.get()));
    if (const std::string err = nlopt_add_constraints(opt.get(), m, options, &ctx, &result);
        !err.empty())
      return fail(err);
    const bool penalty = result.constraints_as_penalty;
    const double weight = options.penalty_weight;
    FiniteDifferences fd(tracker, problem, options,
                         [&tracker, penalty, weight](const ProblemEvaluation& e) {
                           double v = tracker.optimizer_cost(e);
                           if (penalty) {
                             for (double g : e.constraints)
                               v += weight * std::max(g, 0.0) * std::max(g, 0.0);
                           }
                           return v;
                         });
    ctx.fd = &fd;
    if (const std::string err = nlopt_add_local_optimizer(opt.get(), n, options, &result);
        !err.empty())
      return fail(err);

    set_tolerances(opt.get(), options);
    nlopt_set_maxeval(opt.get(),
                      static_cast<int>(std::min<long>(options.max_evaluations, INT_MAX)));
    if (options.max_time > 0.0) nlopt_set_maxtime(opt.get(), options.max_time);

    std::vector<double> x = problem.initial_point();
    const NloptOutcome out = nlopt_optimize_checked(opt.get(), id, options, tracker, ctx, &x);
    nlopt_report(opt.get(), out, options, tracker, x, &result);
  } catch (const std::exception& e) {
    tracker.fail(&result, std::string("NLopt driver: ") + e.what());
  } catch (...) {
    tracker.fail(&result, "NLopt driver: non-standard exception");
  }
  tracker.finish(&result);
  return result;
}

}  // namespace pronk::optimize
