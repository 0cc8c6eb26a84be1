#include <string>

#include "io/load/mechanism_loader.hpp"
#include "sim/pseudorigid/simulator.hpp"

namespace pronk::io {

namespace pr = pronk::pseudorigid;

namespace {

/// The resolved document's chosen settings, rewritten from the mechanism's options.
void write_chosen(const pr::SimulationOptions& o, nlohmann::json* sim) {
  (*sim)["method"] = std::string(ode::to_string(o.solver.method));
  (*sim)["rtol"] = o.solver.rtol;
  (*sim)["atol"] = o.solver.atol;
  (*sim)["h_fixed"] = o.solver.h_fixed;
  (*sim)["energy_tol"] = o.energy_tol;
}

}  // namespace

pr::RunSummary simulate_loaded(LoadedMechanism* loaded) {
  const pr::RunSummary first = pr::simulate(loaded->mechanism);
  if (!loaded->method_auto || first.status != pr::RunStatus::kCompleted ||
      !pr::needs_rerun(loaded->method_choice, first.drift_relative())) {
    return first;
  }
  loaded->method_choice = pr::refine_choice(loaded->method_choice, first.drift_relative());
  pr::SimulationOptions& o = loaded->mechanism.simulation;
  pr::apply_choice(loaded->method_choice, &o.solver, &o.energy_tol);
  write_chosen(o, &loaded->resolved["simulation"]);
  pr::RunSummary second = pr::simulate(loaded->mechanism);
  second.counters += first.counters;
  second.wall_time += first.wall_time;
  return second;
}

}  // namespace pronk::io
