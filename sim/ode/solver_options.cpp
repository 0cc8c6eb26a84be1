// Method names and SolverOptions::validate().
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>

#include "sim/ode/solver.hpp"

namespace pronk::ode {

std::string_view to_string(Method m) {
  switch (m) {
    case Method::kEuler:
      return "euler";
    case Method::kRk2:
      return "rk2";
    case Method::kRk4:
      return "rk4";
    case Method::kDopri5:
      return "dopri5";
    case Method::kRodas4:
      return "rodas4";
    case Method::kRadau5:
      return "radau5";
    case Method::kCvodeBdf:
      return "cvode_bdf";
    case Method::kVerlet:
      return "verlet";
  }
  return "unknown";
}

namespace {

/// The value of `all` whose to_string() is name into *out; false (out unchanged) for none.
template <class E>
bool parse_name(std::string_view name, std::initializer_list<E> all, E* out) {
  for (E e : all) {
    if (name == to_string(e)) {
      *out = e;
      return true;
    }
  }
  return false;
}

}  // namespace

bool parse_method(std::string_view name, Method* out) {
  return parse_name(name,
                    {Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5, Method::kRodas4,
                     Method::kRadau5, Method::kCvodeBdf, Method::kVerlet},
                    out);
}

std::string_view to_string(CvodeLinearSolver s) {
  switch (s) {
    case CvodeLinearSolver::kAuto:
      return "auto";
    case CvodeLinearSolver::kDense:
      return "dense";
    case CvodeLinearSolver::kKlu:
      return "klu";
  }
  return "unknown";
}

bool parse_cvode_linear_solver(std::string_view name, CvodeLinearSolver* out) {
  return parse_name(
      name, {CvodeLinearSolver::kAuto, CvodeLinearSolver::kDense, CvodeLinearSolver::kKlu}, out);
}

std::string_view to_string(EventRestart r) {
  switch (r) {
    case EventRestart::kInterpolant:
      return "interpolant";
    case EventRestart::kStep:
      return "step";
  }
  return "unknown";
}

bool parse_event_restart(std::string_view name, EventRestart* out) {
  return parse_name(name, {EventRestart::kInterpolant, EventRestart::kStep}, out);
}

bool is_adaptive(Method m) {
  return m == Method::kDopri5 || m == Method::kRodas4 || m == Method::kRadau5 ||
         m == Method::kCvodeBdf;
}

namespace {

/// Writes "field: value: rule" into *error (if non-null) and returns false.
bool fail(std::string* error, const char* field, double value, const char* rule) {
  if (error != nullptr) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", value);
    *error = std::string(field) + ": " + buf + ": " + rule;
  }
  return false;
}

/// Checks value > 0 and finite.
bool positive_finite(std::string* error, const char* field, double value) {
  if (!(value > 0.0)) return fail(error, field, value, "must be > 0");
  if (!std::isfinite(value)) return fail(error, field, value, "must be finite");
  return true;
}

/// Checks value >= 0 and finite.
bool nonnegative_finite(std::string* error, const char* field, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    return fail(error, field, value, "must be >= 0 and finite");
  }
  return true;
}

}  // namespace

bool SolverOptions::validate(std::string* error) const {
  if (to_string(method) == "unknown") {
    return fail(error, "method", static_cast<double>(static_cast<int>(method)),
                "must be one of euler, rk2, rk4, dopri5, rodas4, radau5, cvode_bdf, verlet");
  }
  if (!positive_finite(error, "rtol", rtol)) return false;
  if (!positive_finite(error, "atol", atol)) return false;
  if (!positive_finite(error, "h_fixed", h_fixed)) return false;
  if (!nonnegative_finite(error, "h_flight", h_flight)) return false;
  if (!nonnegative_finite(error, "verlet_energy_budget", verlet_energy_budget)) return false;
  if (!(h_initial >= 0.0)) return fail(error, "h_initial", h_initial, "must be >= 0");
  if (!std::isfinite(h_initial)) return fail(error, "h_initial", h_initial, "must be finite");
  if (!(h_max > 0.0)) return fail(error, "h_max", h_max, "must be > 0");
  if (!(h_min >= 0.0)) return fail(error, "h_min", h_min, "must be >= 0");
  if (!(h_min < h_max)) return fail(error, "h_min", h_min, "must be < h_max");
  if (!positive_finite(error, "event_tol", event_tol)) return false;
  if (dense_lu_max_dimension < 0) {
    return fail(error, "dense_lu_max_dimension", dense_lu_max_dimension, "must be >= 0");
  }
  if (max_steps <= 0) {
    return fail(error, "max_steps", static_cast<double>(max_steps), "must be > 0");
  }
  if (!nonnegative_finite(error, "max_steps_per_second", max_steps_per_second)) return false;
  if (error != nullptr) error->clear();
  return true;
}

bool SolverOptions::crawling(long attempts, double simulated) const {
  if (!is_adaptive(method) || !(max_steps_per_second > 0.0)) return false;
  return static_cast<double>(attempts) >
         static_cast<double>(kStepBudgetFloor) + max_steps_per_second * std::max(0.0, simulated);
}

std::string SolverOptions::crawl_reason(long attempts, double simulated, double t) const {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "solver crawling: %ld step attempts for %.6g s simulated up to t = %.9g s "
                "(budget %ld + max_steps_per_second %.3g per simulated second); loosen the "
                "tolerances, soften the stiffest element or raise max_steps_per_second",
                attempts, simulated, t, kStepBudgetFloor, max_steps_per_second);
  return buf;
}

std::string SolverOptions::step_limit_reason(long attempts, double t) const {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "step budget exceeded: %ld step attempts (accepted + rejected, whole run) reached "
                "max_steps = %ld at t = %.9g s; take larger steps or raise max_steps",
                attempts, max_steps, t);
  return buf;
}

}  // namespace pronk::ode
