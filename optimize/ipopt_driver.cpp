#include "optimize/ipopt_driver.hpp"

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpTNLP.hpp>

#include <cmath>
#include <exception>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "optimize/evaluation_tracker.hpp"

namespace pronk::optimize {

namespace {

using detail::EvaluationTracker;
using detail::FiniteDifferences;
using detail::StopCause;
using Ipopt::Index;
using Ipopt::Number;

/// Ipopt's "infinite" bound (nlp_lower/upper_bound_inf default to -/+1e19).
constexpr double kIpoptInfinity = 2e19;

/// Ipopt (MUMPS) is not thread-safe: one solve per process at a time.
std::mutex& ipopt_mutex() {
  static std::mutex m;
  return m;
}

/// Adapter from Problem to Ipopt's TNLP. Every callback catches everything:
/// an exception escaping into Ipopt 3.11 becomes status -101 with its message
/// lost, so causes are recorded in the tracker and `false` is returned.
class ProblemTnlp : public Ipopt::TNLP {
 public:
  ProblemTnlp(const Problem& problem, EvaluationTracker& tracker, FiniteDifferences& fd)
      : tracker_(tracker),
        fd_(fd),
        n_(problem.dimension()),
        m_(problem.num_constraints()),
        lower_(problem.lower_bounds()),
        upper_(problem.upper_bounds()),
        x0_(problem.initial_point()) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_;
    m = m_;
    nnz_jac_g = n_ * m_;  // dense
    nnz_h_lag = 0;        // limited-memory Hessian
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (Index j = 0; j < n; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      x_l[j] = std::isfinite(lower_[ju]) ? lower_[ju] : -kIpoptInfinity;
      x_u[j] = std::isfinite(upper_[ju]) ? upper_[ju] : kIpoptInfinity;
    }
    for (Index i = 0; i < m; ++i) {
      g_l[i] = -kIpoptInfinity;  // g(x) <= 0
      g_u[i] = 0.0;
    }
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index,
                          bool init_lambda, Number*) override {
    if (!init_x || init_z || init_lambda) return false;
    for (Index j = 0; j < n; ++j) x[j] = x0_[static_cast<std::size_t>(j)];
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj_value) override {
    return guarded("eval_f", [&] {
      auto rec = fd_.point(x);
      if (!rec || !rec->eval.ok) return false;  // failures go to Ipopt as failures
      obj_value = rec->eval.cost;
      return true;
    });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    return guarded("eval_grad_f", [&] {
      auto rec = fd_.derivatives(x);
      if (!rec || !rec->eval.ok || !rec->derivatives_ok) return false;
      for (Index j = 0; j < n; ++j) grad_f[j] = rec->gradient[static_cast<std::size_t>(j)];
      return true;
    });
  }

  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    return guarded("eval_g", [&] {
      auto rec = fd_.point(x);
      if (!rec || !rec->eval.ok) return false;
      for (Index i = 0; i < m; ++i) g[i] = rec->eval.constraints[static_cast<std::size_t>(i)];
      return true;
    });
  }

  bool eval_jac_g(Index n, const Number* x, bool, Index m, Index, Index* iRow, Index* jCol,
                  Number* values) override {
    return guarded("eval_jac_g", [&] {
      if (values == nullptr) {
        for (Index i = 0; i < m; ++i) {
          for (Index j = 0; j < n; ++j) {
            iRow[i * n + j] = i;
            jCol[i * n + j] = j;
          }
        }
        return true;
      }
      auto rec = fd_.derivatives(x);
      if (!rec || !rec->eval.ok || !rec->derivatives_ok) return false;
      for (std::size_t k = 0; k < static_cast<std::size_t>(m) * static_cast<std::size_t>(n); ++k)
        values[k] = rec->jacobian[k];
      return true;
    });
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    if (x != nullptr) final_x_.assign(x, x + n);
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number, Number, Number, Number, Number,
                             Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    return guarded("intermediate_callback", [&] { return !tracker_.should_stop(); });
  }

  const std::vector<double>& final_x() const { return final_x_; }

 private:
  template <class F>
  bool guarded(const char* where, F&& f) {
    try {
      return f();
    } catch (const std::exception& e) {
      tracker_.record_error(std::string("exception in Ipopt ") + where + ": " + e.what());
    } catch (...) {
      tracker_.record_error(std::string("non-standard exception in Ipopt ") + where);
    }
    return false;
  }

  EvaluationTracker& tracker_;
  FiniteDifferences& fd_;
  Index n_, m_;
  std::vector<double> lower_, upper_, x0_;
  std::vector<double> final_x_;
};

std::string status_text(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
      return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates:
      return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop:
      return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found:
      return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed:
      return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation:
      return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option:
      return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected:
      return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception:
      return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory:
      return "Insufficient_Memory";
    case Ipopt::Internal_Error:
      return "Internal_Error";
  }
  return "status " + std::to_string(static_cast<int>(s));
}

OptimizerStatus map_status(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
      return OptimizerStatus::kConverged;
    case Ipopt::User_Requested_Stop:
      return OptimizerStatus::kStopped;
    case Ipopt::Maximum_Iterations_Exceeded:
      return OptimizerStatus::kMaxEvaluations;
    case Ipopt::Maximum_CpuTime_Exceeded:
      return OptimizerStatus::kMaxTime;
    default:
      return OptimizerStatus::kFailed;
  }
}

void append(std::string* message, const std::string& part) {
  detail::append_message(message, part);
}

/// Sets one pass-through option with the type Ipopt registered for it.
bool set_option(Ipopt::IpoptApplication& app, const std::string& name, const nlohmann::json& v,
                std::string* error) {
  auto fail = [&](const std::string& rule) {
    if (error != nullptr) *error = "ipopt_options/" + name + ": " + v.dump() + ": " + rule;
    return false;
  };
  Ipopt::SmartPtr<const Ipopt::RegisteredOption> reg = app.RegOptions()->GetOption(name);
  if (!Ipopt::IsValid(reg)) return fail("unknown Ipopt option");
  if (name == "hessian_approximation" && v.is_string() && v.get<std::string>() == "exact")
    return fail("only limited-memory is available (derivatives are finite differences)");
  switch (reg->Type()) {
    case Ipopt::OT_String:
      if (!v.is_string()) return fail("expected a string");
      if (!app.Options()->SetStringValue(name, v.get<std::string>()))
        return fail("value rejected by Ipopt");
      return true;
    case Ipopt::OT_Integer:
      if (!v.is_number_integer()) return fail("expected an integer");
      if (!app.Options()->SetIntegerValue(name, static_cast<Index>(v.get<long long>())))
        return fail("value rejected by Ipopt (out of range)");
      return true;
    case Ipopt::OT_Number:
      if (!v.is_number() || !std::isfinite(v.get<double>())) return fail("expected a number");
      if (!app.Options()->SetNumericValue(name, v.get<double>()))
        return fail("value rejected by Ipopt (out of range)");
      return true;
    default:
      return fail("option of an unsupported type");
  }
}

bool set_options(Ipopt::IpoptApplication& app, const nlohmann::json& options, std::string* error) {
  if (!options.is_object()) {
    if (error != nullptr) *error = "ipopt_options: " + options.dump() + ": expected an object";
    return false;
  }
  for (auto it = options.begin(); it != options.end(); ++it) {
    if (!set_option(app, it.key(), it.value(), error)) return false;
  }
  return true;
}

}  // namespace

bool validate_ipopt_options(const nlohmann::json& options, std::string* error) {
  try {
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication(false, false);
    return set_options(*app, options, error);
  } catch (const std::exception& e) {
    if (error != nullptr) *error = std::string("ipopt_options: ") + e.what();
  } catch (...) {
    if (error != nullptr) *error = "ipopt_options: Ipopt raised an exception";
  }
  return false;
}

OptimizerResult run_ipopt(const Problem& problem, const OptimizerOptions& options,
                          EvaluationObserver* observer) {
  OptimizerResult result;
  result.library = "ipopt";
  result.algorithm = "interior-point (limited-memory Hessian, MUMPS)";
  EvaluationTracker tracker(problem, options, observer);
  FiniteDifferences fd(tracker, problem, options, [&tracker](const ProblemEvaluation& e) {
    return tracker.optimizer_cost(e);
  });
  std::lock_guard<std::mutex> lock(ipopt_mutex());
  try {
    const bool verbose =
        options.ipopt_options.is_object() && options.ipopt_options.contains("print_level");
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app =
        new Ipopt::IpoptApplication(/*create_console_out=*/verbose, false);
    // Our defaults first: the user's pass-through options may override them.
    app->Options()->SetIntegerValue("print_level", 0);
    app->Options()->SetStringValue("sb", "yes");  // no banner
    app->Options()->SetStringValue("hessian_approximation", "limited-memory");
    // Keep iterates inside the bounds the Problem declared (no 1e-8 relaxation).
    app->Options()->SetNumericValue("bound_relax_factor", 0.0);
    std::string error;
    if (!set_options(*app, options.ipopt_options, &error)) {
      result.status = OptimizerStatus::kFailed;
      result.message = error;
      tracker.fill(&result);
      return result;
    }
    // Initialise from an empty stream: Initialize() would silently read ./ipopt.opt.
    std::istringstream no_options_file;
    Ipopt::ApplicationReturnStatus st = app->Initialize(no_options_file);
    if (st != Ipopt::Solve_Succeeded) {
      result.status = OptimizerStatus::kFailed;
      result.library_status = status_text(st);
      result.message = "Ipopt initialisation failed: " + status_text(st);
      tracker.fill(&result);
      return result;
    }
    Ipopt::SmartPtr<ProblemTnlp> tnlp = new ProblemTnlp(problem, tracker, fd);
    st = app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(Ipopt::GetRawPtr(tnlp)));
    result.library_status = status_text(st);
    result.status = map_status(st);
    result.message = "Ipopt: " + result.library_status;
    tracker.apply_stop_cause(&result);
    if (result.status == OptimizerStatus::kConverged && tracker.failed_point(tnlp->final_x())) {
      result.status = OptimizerStatus::kFailed;
      append(&result.message,
             "Ipopt ended at a point whose evaluation failed; the best successful point is "
             "reported");
    }
  } catch (const std::exception& e) {
    tracker.fail(&result, std::string("Ipopt driver: ") + e.what());
  } catch (...) {
    tracker.fail(&result, "Ipopt driver: non-standard exception");
  }
  tracker.finish(&result);
  return result;
}

}  // namespace pronk::optimize
