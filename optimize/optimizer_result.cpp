#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

#include "optimize/optimizer.hpp"

namespace pronk::optimize {

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

std::string OptimizerResult::brief_report() const {
  std::ostringstream s;
  s << library << ' ' << algorithm << ": " << to_string(status);
  if (!library_status.empty()) s << " (" << library_status << ")";
  s << ", " << evaluations << " evaluations (" << failed_evaluations << " failed)";
  if (best_index >= 0) {
    s << ", best cost " << fmt("%.6g", best_cost) << (best_feasible ? " feasible" : " infeasible")
      << " at #" << best_index;
  } else {
    s << ", no successful evaluation";
  }
  s << ", " << fmt("%.3f", wall_time) << " s";
  return s.str();
}

std::string OptimizerResult::full_report(const Problem& problem) const {
  std::ostringstream s;
  auto row = [&](const std::string& key, const std::string& value) {
    std::string k = key;
    k.resize(std::max<std::size_t>(k.size(), 22), ' ');
    s << k << value << '\n';
  };
  row("optimizer", library + " " + algorithm);
  row("status",
      std::string(to_string(status)) + (library_status.empty() ? "" : " (" + library_status + ")"));
  row("message", message);
  row("constraints",
      problem.num_constraints() == 0
          ? "none"
          : (constraints_as_penalty ? "quadratic penalty in the cost" : "passed to the optimizer"));
  row("evaluations", std::to_string(evaluations) + " (finite-difference " +
                         std::to_string(gradient_evaluations) + ", failed " +
                         std::to_string(failed_evaluations) + ", non-finite " +
                         std::to_string(nonfinite_evaluations) + ")");
  row("wall time [s]",
      fmt("%.3f", wall_time) + " (in evaluations " + fmt("%.3f", evaluation_time) + ")");
  if (best_index < 0) {
    row("best", "none (no evaluation succeeded)");
    return s.str();
  }
  row("best", std::string(1, '#').append(std::to_string(best_index)) + ", cost " +
                  fmt("%.9g", best_cost) +
                  (best_feasible ? ", feasible" : ", INFEASIBLE (least violation found)"));

  const auto names = problem.variable_names();
  const auto lo = problem.lower_bounds(), hi = problem.upper_bounds();
  std::size_t w = 8;
  for (const auto& n : names) w = std::max(w, n.size());
  const auto cnames = problem.constraint_names();
  for (const auto& n : cnames) w = std::max(w, n.size());
  char line[512];
  std::snprintf(line, sizeof line, "  %-*s %16s %16s %16s\n", static_cast<int>(w), "variable",
                "value", "lower", "upper");
  s << line;
  for (std::size_t j = 0; j < best_x.size(); ++j) {
    const std::string name =
        j < names.size() ? names[j] : std::string(1, 'x').append(std::to_string(j));
    std::snprintf(line, sizeof line, "  %-*s %16.9g %16.9g %16.9g\n", static_cast<int>(w),
                  name.c_str(), best_x[j], j < lo.size() ? lo[j] : 0.0,
                  j < hi.size() ? hi[j] : 0.0);
    s << line;
  }
  if (!best_constraints.empty()) {
    std::snprintf(line, sizeof line, "  %-*s %16s %16s\n", static_cast<int>(w), "constraint",
                  "g(x) (<= 0)", "state");
    s << line;
    for (std::size_t i = 0; i < best_constraints.size(); ++i) {
      const std::string name =
          i < cnames.size() ? cnames[i] : std::string(1, 'g').append(std::to_string(i));
      const double g = best_constraints[i];
      std::snprintf(line, sizeof line, "  %-*s %16.9g %16s\n", static_cast<int>(w), name.c_str(), g,
                    (g > 0.0 && !best_feasible) ? "violated" : (g > -1e-6 ? "active" : "inactive"));
      s << line;
    }
  }
  return s.str();
}

}  // namespace pronk::optimize
