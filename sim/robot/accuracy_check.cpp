#include "sim/robot/accuracy_check.hpp"

#include <cstdio>

#include "sim/ode/solver.hpp"

namespace pronk::robot {

namespace {

/// "verlet h = 0.00015 s" or "rodas4 rtol 1e-06": the integration a run used.
std::string method_text(ode::Method method, double h, double rtol) {
  char buf[96];
  if (method == ode::Method::kVerlet) {
    std::snprintf(buf, sizeof buf, "verlet h = %.2g s", h);
  } else {
    std::snprintf(buf, sizeof buf, "%s rtol %.2g", std::string(ode::to_string(method)).c_str(),
                  rtol);
  }
  return buf;
}

}  // namespace

AccuracyCheck check_accuracy(const scene::Scene& scene, const RobotRunResult& run) {
  AccuracyCheck c;
  const RobotMonitors& m = run.monitors;
  c.drift_relative = m.drift_relative();
  c.accuracy = scene.pseudo_rigid.accuracy;
  if (m.method_auto) {
    const pseudorigid::MethodChoice& k = m.method_choice;
    c.method = "auto: " + method_text(k.method, k.h_fixed, k.rtol) +
               (k.reruns > 0 ? ", already rerun once tighter" : "");
  } else {
    const ode::SolverOptions& s = scene.pseudo_rigid.solver;
    c.method = method_text(s.method, s.h_fixed, s.rtol) + ", named by the scene: nothing reruns it";
  }
  c.beyond = m.energy_measured && run.run.status == reduced::RunStatus::kCompleted &&
             c.drift_relative > c.accuracy;
  return c;
}

void add_accuracy_warning(const AccuracyCheck& check, std::map<std::string, long>* warnings) {
  if (check.beyond) (*warnings)["energy_beyond_accuracy"] = 1;
}

std::string accuracy_warning_text(const AccuracyCheck& check) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "energy balance drifted %.2g of its scale, beyond the accuracy %.2g (%s); a "
                "smaller step or tolerance, or \"method\": \"auto\" with a tighter "
                "\"accuracy\", keeps it",
                check.drift_relative, check.accuracy, check.method.c_str());
  return buf;
}

}  // namespace pronk::robot
