// `pronk bench`'s check of "method": "auto" against the fastest method at the same accuracy,
// per scene (auto_check.hpp).
#include "app/bench/auto_check.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/method_choice.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/robot/robot_simulator.hpp"

namespace pronk::app::bench {

namespace pr = pronk::pseudorigid;
using nlohmann::json;

namespace {

constexpr double kGiveUp = 5.0;  ///< a family stops once a run costs this times the best

/// A scene of the check: its document (duration set) and kind.
struct CheckScene {
  std::string name;
  bool robot = false;
  json doc;
  double t_end = 0.0;
};

/// What one run gave.
struct Outcome {
  std::string status;
  long steps = 0, rejected = 0;
  double drift = 0.0;  ///< relative to the energy scale
  std::string choice;  ///< auto's reason ("" otherwise)
};

/// The "solver" settings of run r (mechanism "simulation" keys or the robot's "solver").
json solver_settings(const AutoRun& r, double accuracy) {
  json s = {{"method", r.method}};
  if (r.method == "auto") {
    s["accuracy"] = accuracy;
  } else if (r.method == "verlet") {
    s["h_fixed"] = r.h;
    s["energy_tol"] = r.energy_tol;
  } else {
    s["rtol"] = r.tol;
    s["atol"] = r.tol;
  }
  return s;
}

json with_settings(const CheckScene& s, const AutoRun& r, double accuracy) {
  json d = s.doc;
  const json settings = solver_settings(r, accuracy);
  if (s.robot) {
    d["pseudo_rigid"]["solver"] = settings;
  } else {
    // The scene's own step or tolerances give way to the run's (auto refuses them).
    for (const char* k : pr::kAutoChosenSettings) d["simulation"].erase(k);
    for (auto it = settings.begin(); it != settings.end(); ++it) {
      d["simulation"][it.key()] = it.value();
    }
  }
  return d;
}

Outcome run_mechanism(const CheckScene& s, const json& doc) {
  io::LoadedMechanism l = io::parse_mechanism(doc, s.name);
  const pr::RunSummary r = io::simulate_loaded(&l);  // auto's rerun, when it needs one, counts
  Outcome o;
  o.status = std::string(pr::to_string(r.status));
  o.steps = r.counters.steps_accepted;
  o.rejected = r.counters.steps_rejected;
  o.drift = r.drift_relative();
  if (l.method_auto) o.choice = l.method_choice.reason;
  return o;
}

Outcome run_robot(const CheckScene& s, const json& doc) {
  const scene::Scene sc = io::parse_scene(doc, s.name);
  const robot::RobotRunResult r = robot::simulate(sc);
  Outcome o;
  o.status = std::string(reduced::to_string(r.run.status));
  o.steps = r.run.cost.solver.steps_accepted;
  o.rejected = r.run.cost.solver.steps_rejected;
  const robot::RobotMonitors& m = r.monitors;
  o.drift = m.drift_relative();
  if (m.method_auto) o.choice = m.method_choice.reason;
  return o;
}

/// Runs r on s: once, and `repeat` times (median CPU) unless the first run already costs more
/// than `cap` [s]. Loading the scene is timed too (auto probes there).
AutoRun measure(const CheckScene& s, AutoRun r, double accuracy, int repeat, double cap,
                std::string* choice) {
  const json doc = with_settings(s, r, accuracy);
  const Timed<Outcome> run = timed(
      repeat, [&] { return s.robot ? run_robot(s, doc) : run_mechanism(s, doc); },
      [&](const Outcome& o, double cpu) { return cpu > cap || o.status != "completed"; });
  const Outcome& o = run.result;
  r.cpu_s = run.cpu_s;
  r.status = o.status;
  r.steps = o.steps;
  r.rejected = o.rejected;
  r.drift = o.drift;
  r.meets = o.status == "completed" && o.drift <= accuracy;
  if (choice != nullptr) *choice = o.choice;
  return r;
}

/// Runs one family from cheap to expensive into out->grid: stops at the first run that meets
/// the accuracy or costs more than kGiveUp x the best so far (*best_cpu, updated).
void run_family(const CheckScene& s, const std::vector<AutoRun>& family, const BenchConfig& c,
                AutoCheck* out, double* best_cpu) {
  for (const AutoRun& point : family) {
    const double cap = *best_cpu < std::numeric_limits<double>::infinity()
                           ? kGiveUp * *best_cpu
                           : std::numeric_limits<double>::infinity();
    const AutoRun r = measure(s, point, out->accuracy, c.repeat, cap, nullptr);
    out->grid.push_back(r);
    if (r.meets) {
      *best_cpu = std::min(*best_cpu, r.cpu_s);
      return;
    }
    if (r.cpu_s > cap) return;
  }
}

AutoRun setting(const std::string& method, double h, double energy_tol, double tol) {
  AutoRun r;
  r.method = method;
  r.h = h;
  r.energy_tol = energy_tol;
  r.tol = tol;
  return r;
}

/// The grid's families: verlet per energy budget over the steps, then each adaptive method
/// over the tolerances.
std::vector<std::vector<AutoRun>> families(const BenchConfig& c, double accuracy) {
  std::vector<double> steps, tols;
  if (c.quick) {
    steps = {1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5};
    tols = {1e-4, 1e-6};
  } else {
    for (double h = 2e-3; h > 3e-5; h /= std::sqrt(2.0)) steps.push_back(h);
    for (double t = 1e-3; t > 5e-10; t /= 10.0) tols.push_back(t);
  }
  std::vector<std::vector<AutoRun>> out;
  const std::vector<double> budgets = c.quick
                                          ? std::vector<double>{0.0, accuracy / 2}
                                          : std::vector<double>{0.0, accuracy / 2, accuracy / 10};
  for (double et : budgets) {
    std::vector<AutoRun> f;
    for (double h : steps) f.push_back(setting("verlet", h, et, 0.0));
    out.push_back(f);
  }
  const std::vector<std::string> methods =
      c.quick ? std::vector<std::string>{"dopri5", "rodas4"}
              : std::vector<std::string>{"dopri5", "rodas4", "radau5", "cvode_bdf"};
  for (const std::string& m : methods) {
    std::vector<AutoRun> f;
    for (double t : tols) f.push_back(setting(m, 0.0, 0.0, t));
    out.push_back(f);
  }
  return out;
}

/// The largest step at which plain verlet completed (infinity when none did).
double largest_stable_step(const std::vector<AutoRun>& grid) {
  double h = 0.0;
  for (const AutoRun& r : grid) {
    if (r.method == "verlet" && r.energy_tol == 0.0 && r.status == "completed") {
      h = std::max(h, r.h);
    }
  }
  return h > 0.0 ? h : std::numeric_limits<double>::infinity();
}

AutoCheck check_scene(const CheckScene& s, const BenchConfig& c) {
  AutoCheck out;
  out.scene = s.name;
  out.kind = s.robot ? "robot" : "mechanism";
  out.t_end = s.t_end;
  out.accuracy = pr::AutoRequest{}.accuracy;
  out.auto_run = measure(s, setting("auto", 0.0, 0.0, 0.0), out.accuracy, c.repeat,
                         std::numeric_limits<double>::infinity(), &out.choice);
  double best_cpu = std::numeric_limits<double>::infinity();
  for (auto f : families(c, out.accuracy)) {
    // Budgeted verlet starts where plain verlet is stable (beyond, sub-stepping merely
    // rescues an unstable step, at great cost).
    if (f.front().method == "verlet" && f.front().energy_tol > 0.0) {
      const double stable = largest_stable_step(out.grid);
      std::erase_if(f, [&](const AutoRun& r) { return r.h > stable * (1.0 + 1e-12); });
    }
    run_family(s, f, c, &out, &best_cpu);
  }
  for (size_t i = 0; i < out.grid.size(); ++i) {
    const AutoRun& r = out.grid[i];
    if (r.meets && (out.best < 0 || r.cpu_s < out.grid[static_cast<size_t>(out.best)].cpu_s)) {
      out.best = static_cast<int>(i);
    }
  }
  if (out.best >= 0) {
    out.ratio = out.auto_run.cpu_s / out.grid[static_cast<size_t>(out.best)].cpu_s;
  }
  out.within = out.auto_run.meets && out.best >= 0 && out.ratio <= kAutoRatioTarget;
  return out;
}

/// Every shipped mechanism scene (sorted by name), the quad hopper drop and pr_running.
std::vector<CheckScene> check_scenes(const BenchConfig& c) {
  const double cap = c.quick ? 1.0 : std::numeric_limits<double>::infinity();
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(c.studies_dir + "/mechanisms")) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<CheckScene> out;
  for (const auto& f : files) {
    CheckScene s{.name = f.stem().string(), .doc = io::read_json_file(f.string())};
    s.t_end = std::min(cap, s.doc["simulation"].value("t_end", 1.0));
    s.doc["simulation"]["t_end"] = s.t_end;
    out.push_back(s);
  }
  const double quad_end = c.quick ? 1.0 : 10.0;
  out.push_back(
      {.name = "quad_hopper_mechanism", .doc = quad_hopper_mechanism(quad_end), .t_end = quad_end});
  CheckScene running{.name = "pr_running",
                     .robot = true,
                     .doc = io::read_json_file(c.studies_dir + "/scenes/pr_running.json")};
  running.t_end = c.quick ? 0.6 : running.doc["simulation"].value("duration", 10.0);
  running.doc["simulation"]["duration"] = running.t_end;
  out.push_back(running);
  return out;
}

json to_json(const AutoRun& r) {
  json j = {{"method", r.method}, {"status", r.status},     {"cpu_s", r.cpu_s},
            {"steps", r.steps},   {"rejected", r.rejected}, {"energy_drift_rel", r.drift},
            {"meets", r.meets}};
  if (r.method == "verlet") {
    j["h"] = r.h;
    j["energy_tol"] = r.energy_tol;
  } else if (r.method != "auto") {
    j["tol"] = r.tol;
  }
  return j;
}

}  // namespace

std::vector<AutoCheck> auto_check(const BenchConfig& c) {
  std::vector<AutoCheck> out;
  for (const CheckScene& s : check_scenes(c)) out.push_back(check_scene(s, c));
  return out;
}

json to_json(const AutoCheck& a) {
  json j = {{"scene", a.scene},       {"kind", a.kind},     {"t_end", a.t_end},
            {"accuracy", a.accuracy}, {"choice", a.choice}, {"auto", to_json(a.auto_run)},
            {"ratio", a.ratio},       {"within", a.within}, {"target_ratio", kAutoRatioTarget}};
  j["best"] = a.best >= 0 ? to_json(a.grid[static_cast<size_t>(a.best)]) : json(nullptr);
  j["grid"] = json::array();
  for (const AutoRun& r : a.grid) j["grid"].push_back(to_json(r));
  return j;
}

}  // namespace pronk::app::bench
