#include "app/bench_command.hpp"

#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/bench_suite.hpp"
#include "sim/io/atomic_file.hpp"
#include "sim/io/build_info.hpp"
#include "sim/io/input_error.hpp"
#include "sim/io/plot.hpp"

#ifndef PRONK_STUDIES_DIR
#define PRONK_STUDIES_DIR "studies"
#endif

namespace pronk::app {

using bench::FidelityPoint;
using bench::WorkPoint;
using nlohmann::json;

CLI::App* add_bench_command(CLI::App& app, BenchArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Measure speed versus accuracy (SPEC 7): work-precision of every solver on the\n"
      "pseudo-rigid satellite (tolerances 1e-3..1e-10, internal stiffness 1e4..1e8 N/m)\n"
      "and the reduced legged hopper (steps, tolerances, stride-map fixed point), the\n"
      "fidelity ladder (impulse, pulse, rigid body, pseudo-rigid: apexes, stride-map spectral\n"
      "radius, robustness to seeded disturbances at duty 10-40 %), the quad hopper drop\n"
      "(four-mass and rigid body), and the\n"
      "peers SUNDIALS CVODE and MuJoCo when they were built. Writes bench.json,\n"
      "work_precision.csv, fidelity_ladder.csv, fidelity_robustness.csv and SVG diagrams.");
  cmd->add_flag("--quick", args.quick, "CI size: fewer points and shorter runs (< 1 min)");
  cmd->add_option("--out", args.out_dir, "Output directory (default: out/bench)");
  cmd->add_option("--repeat", args.repeat,
                  "Timed repeats per point, median reported (default 3; 1 with --quick)")
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("--no-peers", args.no_peers, "Do not run the CVODE and MuJoCo peers");
  cmd->add_option("--studies", args.studies_dir,
                  "The studies/ directory with the shipped scenes (default: the source tree's)");
  cmd->add_flag("--quiet,-q", args.quiet, "Print nothing on success");
  return cmd;
}

namespace {

json to_json(const WorkPoint& p) {
  json j = {{"problem", p.problem}, {"solver", p.solver},
            {"variant", p.variant}, {"stiffness", p.stiffness},
            {"tol", p.tol},         {"h", p.h},
            {"t_end", p.t_end},     {"status", p.status},
            {"wall_s", p.wall_s},   {"cpu_s", p.cpu_s},
            {"steps", p.steps},     {"rejected", p.rejected},
            {"rhs", p.rhs},         {"jacobians", p.jacobians},
            {"lu", p.lu},           {"errors", json::object()}};
  for (const auto& [k, v] : p.errors) {
    if (std::isfinite(v)) j["errors"][k] = v;
  }
  return j;
}

json to_json(const FidelityPoint& p) {
  return {{"model", p.model},
          {"available", p.available},
          {"note", p.note},
          {"pulse_duration", p.pulse_duration},
          {"status", p.status},
          {"t_end", p.t_end},
          {"wall_s", p.wall_s},
          {"cpu_s", p.cpu_s},
          {"cost_per_sim_s", p.cost_per_sim_s},
          {"strides", p.strides},
          {"mean_duty", p.mean_duty},
          {"mean_apex_m", p.mean_apex},
          {"apex_rms_vs_impulse_m", p.apex_rms_vs_impulse},
          {"spectral_radius", p.spectral_radius},
          {"spectral_radius_method", p.spectral_radius_method},
          {"spectral_radius_fit", p.spectral_radius_fit},
          {"fit_ok", p.fit_ok},
          {"fit_residual_rel", p.fit_residual_rel},
          {"stable", p.stable},
          {"fixed_point_vs_impulse", p.fixed_point_vs_impulse},
          {"apex_max_vs_four_mass_m", p.apex_max_vs_four_mass}};
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

json to_json(const bench::LadderRobustness& lr) {
  json rungs = json::array();
  for (const auto& r : lr.rungs) {
    json cells = json::array();
    for (const auto& c : r.cells) {
      cells.push_back({{"duty", c.duty},
                       {"trials", c.trials},
                       {"stabilized", c.stabilized},
                       {"stabilized_fraction", c.fraction},
                       {"fell", c.fell},
                       {"mean_duty", c.mean_duty},
                       {"spectral_radius", c.spectral_radius},
                       {"only_this", c.only_this},
                       {"only_pulse", c.only_pulse}});
    }
    json j = {{"model", r.model}, {"available", r.available}, {"note", r.note}, {"cells", cells}};
    if (r.available) {
      j["boundary_status"] = r.boundary_status;
      j["boundary"] = r.boundary;
      j["bracket_bad"] = r.bad;
      j["first_good"] = r.first_good;
      j["probes"] = r.probes;
      j["disagreements_vs_pulse"] = r.disagreements_vs_pulse;
      j["cpu_s"] = r.cpu_s;
    }
    rungs.push_back(j);
  }
  return {{"study", lr.study},
          {"trials_per_cell", lr.trials},
          {"seed", lr.seed},
          {"trial_duration_s", lr.trial_duration},
          {"duties", lr.duties},
          {"boundary_resolution", lr.resolution},
          {"definitions",
           {{"stabilized",
             "pronk map's: no fall, settled (position, tilt, apex) by stride 30 and "
             "held for 3 strides to the end of the trial"},
            {"boundary",
             "largest duty at which every trial stabilizes: the last good cell, bisected "
             "towards the next until the bracket [boundary, bracket_bad] is at most "
             "boundary_resolution wide (status all_good: >= the last duty; none_good: < the "
             "first)"},
            {"disagreements_vs_pulse",
             "trials this rung stabilizes and the pulse rung does not (only_this) or the "
             "reverse (only_pulse), same trials"},
            {"spectral_radius",
             "undisturbed gait at the duty: stride map (impulse, pulse), fitted estimate "
             "(rigid, pseudo_rigid); 10 = no orbit / no estimate"}}},
          {"rungs", rungs}};
}

std::string robustness_csv(const bench::LadderRobustness& lr) {
  std::string s =
      "model,duty,trials,stabilized,stabilized_fraction,fell,mean_duty,spectral_radius,only_this,"
      "only_pulse,boundary_status,boundary,disagreements_vs_pulse\n";
  for (const auto& r : lr.rungs) {
    if (!r.available) {
      s += r.model + ",,,,,,,,,,not_available,,\n";
      continue;
    }
    for (const auto& c : r.cells) {
      s += r.model + "," + fmt(c.duty) + "," + std::to_string(c.trials) + "," +
           std::to_string(c.stabilized) + "," + fmt(c.fraction) + "," + std::to_string(c.fell) +
           "," + fmt(c.mean_duty) + "," + fmt(c.spectral_radius) + "," +
           std::to_string(c.only_this) + "," + std::to_string(c.only_pulse) + "," +
           r.boundary_status + "," + fmt(r.boundary) + "," +
           std::to_string(r.disagreements_vs_pulse) + "\n";
    }
  }
  return s;
}

/// Stabilized fraction vs duty per rung (linear axes), the boundaries as vertical marks.
std::string robustness_script(const bench::LadderRobustness& lr) {
  std::string s =
      "set terminal svg size 900,560 dynamic enhanced font 'Helvetica,11'\n"
      "set output 'fidelity_robustness.svg'\n"
      "set title 'Fidelity ladder: fraction of " +
      std::to_string(lr.trials) +
      " seeded disturbance trials stabilized (map_seed_duty, row 0)' noenhanced\n"
      "set xlabel 'duty cycle [-]'\nset ylabel 'stabilized fraction [-]'\n"
      "set yrange [-0.05:1.05]\nset offsets 0.05, 0.05, 0, 0\nset grid\n"
      "set key outside right\n";
  std::string plot = "plot ";
  int i = 0;
  for (const auto& r : lr.rungs) {
    if (!r.available || r.cells.empty()) continue;
    s += "$d" + std::to_string(i) + " << EOD\n";
    for (const auto& c : r.cells) s += fmt(c.duty) + " " + fmt(c.fraction) + "\n";
    s += "EOD\n";
    plot += std::string(i ? ", " : "") + "$d" + std::to_string(i) +
            // Rungs that agree draw on top of each other: distinct points, widths and dashes.
            " using 1:2 with linespoints lw " + std::to_string(3 - i) + " dt " +
            std::to_string(i + 1) + " pt " + std::to_string(4 + 2 * i) + " ps 1.5 title '" +
            r.model + " (boundary " + r.boundary_status + " " + fmt(r.boundary) + ")' noenhanced";
    ++i;
  }
  if (i == 0) return "";
  return s + plot + "\n";
}

std::string work_precision_csv(const std::vector<WorkPoint>& pts) {
  const std::array<const char*, 7> errs = {"omega_final",    "omega_l2",       "final_state",
                                           "l2_series",      "touchdown_time", "fixed_point",
                                           "spectral_radius"};
  std::string s =
      "problem,solver,variant,stiffness,tol,h,t_end,status,wall_s,cpu_s,steps,rejected,rhs,"
      "jacobians,lu";
  for (const char* e : errs) s += std::string(",err_") + e;
  s += "\n";
  for (const auto& p : pts) {
    s += p.problem + "," + p.solver + "," + p.variant + "," + fmt(p.stiffness) + "," + fmt(p.tol) +
         "," + fmt(p.h) + "," + fmt(p.t_end) + "," + p.status + "," + fmt(p.wall_s) + "," +
         fmt(p.cpu_s) + "," + std::to_string(p.steps) + "," + std::to_string(p.rejected) + "," +
         std::to_string(p.rhs) + "," + std::to_string(p.jacobians) + "," + std::to_string(p.lu);
    for (const char* e : errs) {
      auto it = p.errors.find(e);
      s += ",";
      if (it != p.errors.end()) s += fmt(it->second);
    }
    s += "\n";
  }
  return s;
}

std::string ladder_csv(const std::vector<FidelityPoint>& pts) {
  std::string s =
      "model,available,pulse_duration,status,t_end,wall_s,cpu_s,cost_per_sim_s,strides,mean_duty,"
      "mean_apex_m,apex_rms_vs_impulse_m,spectral_radius,spectral_radius_method,"
      "spectral_radius_fit,fit_ok,stable,fixed_point_vs_impulse,apex_max_vs_four_mass_m,note\n";
  for (const auto& p : pts) {
    s += p.model + "," + (p.available ? "1" : "0") + "," + fmt(p.pulse_duration) + "," + p.status +
         "," + fmt(p.t_end) + "," + fmt(p.wall_s) + "," + fmt(p.cpu_s) + "," +
         fmt(p.cost_per_sim_s) + "," + std::to_string(p.strides) + "," + fmt(p.mean_duty) + "," +
         fmt(p.mean_apex) + "," + fmt(p.apex_rms_vs_impulse) + "," + fmt(p.spectral_radius) + "," +
         p.spectral_radius_method + "," + fmt(p.spectral_radius_fit) + "," +
         (p.fit_ok ? "1" : "0") + "," + (p.stable ? "1" : "0") + "," +
         fmt(p.fixed_point_vs_impulse) + "," + fmt(p.apex_max_vs_four_mass) + ",\"" + p.note +
         "\"\n";
  }
  return s;
}

/// One curve of a diagram: (x, y) pairs.
struct Series {
  std::string title;
  std::vector<std::pair<double, double>> xy;
};

/// A log-log gnuplot script with the data inline ($d0 << EOD ...), so the .gp
/// alone reproduces the figure.
std::string loglog_script(const std::string& name, const std::string& title,
                          const std::string& xlabel, const std::string& ylabel,
                          const std::vector<Series>& series) {
  std::string s =
      "set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'\n"
      "set output '" +
      name + ".svg'\nset title '" + title + "'\nset xlabel '" + xlabel + "'\nset ylabel '" +
      ylabel +
      "'\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
      "set grid\nset key outside right\n";
  std::string plot = "plot ";
  int i = 0;
  for (const auto& se : series) {
    if (se.xy.empty()) continue;
    s += "$d" + std::to_string(i) + " << EOD\n";
    for (const auto& [x, y] : se.xy) s += fmt(x) + " " + fmt(y) + "\n";
    s += "EOD\n";
    plot += std::string(i ? ", " : "") + "$d" + std::to_string(i) +
            " using 1:2 with linespoints title '" + se.title + "' noenhanced";
    ++i;
  }
  if (i == 0) return "";
  return s + plot + "\n";
}

/// Work-precision series: error `err` vs wall time per (solver, variant) of `problem`.
std::vector<Series> wp_series(const std::vector<WorkPoint>& pts, const std::string& problem,
                              const std::string& err) {
  std::map<std::string, Series> by;
  for (const auto& p : pts) {
    if (p.problem != problem || p.status != "completed") continue;
    auto it = p.errors.find(err);
    if (it == p.errors.end() || !(it->second > 0) || !(p.cpu_s > 0)) continue;
    const std::string key = p.solver + (p.variant.empty() ? "" : " (" + p.variant + " norm)");
    by[key].title = key;
    by[key].xy.push_back({p.cpu_s, it->second});
  }
  std::vector<Series> out;
  for (auto& [k, v] : by) out.push_back(v);
  return out;
}

std::string executable_dir() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : p.parent_path().string();
}

/// Runs a peer executable beside pronk; returns its JSON, or {available: false}.
json run_peer(const std::string& name, const std::string& what, const BenchArgs& args, int repeat,
              bool* failed, const std::string& extra_args = "") {
  const std::string exe = executable_dir() + "/" + name;
  if (access(exe.c_str(), X_OK) != 0) {
    return {{"available", false},
            {"reason", name + " not built: " + what + " was not found when pronk was configured"}};
  }
  const std::string cmd = "'" + exe + "'" + (args.quick ? " --quick" : "") + " --repeat " +
                          std::to_string(repeat) + extra_args;
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) {
    *failed = true;
    return {{"available", false}, {"reason", "could not start " + exe}};
  }
  std::string out;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) out.append(buf.data(), n);
  const int rc = pclose(f);
  json j = json::parse(out, nullptr, false);
  if (rc != 0 || j.is_discarded()) {
    *failed = true;
    return {{"available", false},
            {"reason", name + " failed (exit status " + std::to_string(rc) + ")"}};
  }
  j["available"] = true;
  return j;
}

/// Fastest wall time among `pts` of `problem`/`solver` whose omega_final <= limit.
const WorkPoint* fastest_within(const std::vector<WorkPoint>& pts, const std::string& problem,
                                const std::string& solver, double stiffness, double limit) {
  const WorkPoint* best = nullptr;
  for (const auto& p : pts) {
    if (p.problem != problem || p.solver != solver || p.stiffness != stiffness) continue;
    auto it = p.errors.find("omega_final");
    if (p.status != "completed" || it == p.errors.end() || it->second > limit) continue;
    if (!best || p.cpu_s < best->cpu_s) best = &p;
  }
  return best;
}

const WorkPoint* find_point(const std::vector<WorkPoint>& pts, const std::string& problem,
                            const std::string& solver, const std::string& variant, double k) {
  for (const auto& p : pts) {
    if (p.problem == problem && p.solver == solver && p.variant == variant && p.stiffness == k) {
      return &p;
    }
  }
  return nullptr;
}

json point_brief(const WorkPoint* p) {
  if (!p) return {{"found", false}};
  json j = {{"solver", p->solver}, {"variant", p->variant}, {"tol", p->tol}, {"wall_s", p->wall_s},
            {"cpu_s", p->cpu_s},   {"steps", p->steps},     {"rhs", p->rhs}};
  if (p->errors.count("omega_final")) j["omega_final"] = p->errors.at("omega_final");
  return j;
}

/// The headline ratios against the targets of issues 3, 4 and 7.
json headline(const std::vector<WorkPoint>& sat, const std::vector<WorkPoint>& sweep,
              const json& drop, const json& cvode, const json& mujoco) {
  json h;
  const double limit = 1e-5;
  const WorkPoint* rodas = fastest_within(sat, "satellite", "rodas4", 1e6, limit);
  const WorkPoint* dopri = fastest_within(sat, "satellite", "dopri5", 1e6, limit);
  h["satellite"]["omega_error_limit"] = limit;
  h["satellite"]["rodas4"] = point_brief(rodas);
  h["satellite"]["dopri5"] = point_brief(dopri);
  if (rodas && dopri) h["satellite"]["dopri5_over_rodas4"] = dopri->cpu_s / rodas->cpu_s;
  h["satellite"]["anchor_cvode_issue3_s"] = 0.35;
  if (rodas) h["satellite"]["anchor_over_rodas4"] = 0.35 / rodas->cpu_s;
  // The fastest pronk setting of any solver within the limit (issue 3's target is pronk's).
  const WorkPoint* fastest = nullptr;
  for (const char* solver : {"rodas4", "radau5", "dopri5", "rk4", "verlet"}) {
    const WorkPoint* p = fastest_within(sat, "satellite", solver, 1e6, limit);
    if (p && (!fastest || p->cpu_s < fastest->cpu_s)) fastest = p;
  }
  h["satellite"]["fastest"] = point_brief(fastest);
  if (fastest) {
    h["satellite"]["fastest"]["h"] = fastest->h;
    h["satellite"]["anchor_over_fastest"] = 0.35 / fastest->cpu_s;
  }
  if (cvode.value("available", false) && rodas) {
    double best = -1;
    json best_run;
    for (const auto& r : cvode["satellite"]) {
      if (r.value("status", "") != "completed" || r["omega_final"].get<double>() > limit) continue;
      if (best < 0 || r["cpu_s"].get<double>() < best) {
        best = r["cpu_s"];
        best_run = r;
      }
    }
    if (best > 0) {
      h["satellite"]["cvode"] = best_run;
      h["satellite"]["cvode_over_rodas4"] = best / rodas->cpu_s;
      h["satellite"]["target_cvode_over_rodas4"] = 10.0;
      if (fastest) h["satellite"]["cvode_over_fastest"] = best / fastest->cpu_s;
    }
  }
  for (const std::string v : {"state", "body"}) {
    const WorkPoint* lo = find_point(sweep, "satellite_stiffness", "rodas4", v, 1e4);
    const WorkPoint* hi = find_point(sweep, "satellite_stiffness", "rodas4", v, 1e8);
    if (lo && hi && lo->cpu_s > 0) {
      h["stiffness_growth"]["rodas4_" + v + "_norm"] = {
          {"cpu_1e4_s", lo->cpu_s},
          {"cpu_1e8_s", hi->cpu_s},
          {"ratio", hi->cpu_s / lo->cpu_s},
          {"steps_ratio", static_cast<double>(hi->steps) / std::max(1L, lo->steps)}};
    }
  }
  for (const char* solver : {"radau5", "verlet"}) {
    const WorkPoint* lo = nullptr;
    const WorkPoint* hi = nullptr;
    for (const auto& p : sweep) {
      if (p.problem != "satellite_stiffness" || p.solver != solver) continue;
      if (p.stiffness == 1e4) lo = &p;
      if (p.stiffness == 1e8) hi = &p;
    }
    if (lo && hi && lo->cpu_s > 0) {
      h["stiffness_growth"][solver] = {
          {"cpu_1e4_s", lo->cpu_s},
          {"cpu_1e8_s", hi->cpu_s},
          {"ratio", hi->cpu_s / lo->cpu_s},
          {"steps_ratio", static_cast<double>(hi->steps) / std::max(1L, lo->steps)}};
    }
  }
  h["stiffness_growth"]["target_ratio"] = 3.0;
  if (cvode.value("available", false) && cvode.contains("stiffness")) {
    double lo = -1, hi = -1;
    for (const auto& r : cvode["stiffness"]) {
      if (r["variant"] != "dense_analytic") continue;
      if (r["stiffness"].get<double>() == 1e4) lo = r["cpu_s"];
      if (r["stiffness"].get<double>() == 1e8) hi = r["cpu_s"];
    }
    if (lo > 0 && hi > 0) h["stiffness_growth"]["cvode_dense_analytic"] = {{"ratio", hi / lo}};
  }
  // Quad hopper: the fastest pronk run with energy-balance drift <= 1e-3 of the drop
  // energy (issue 4) vs MuJoCo Euler at 1 ms, per simulated second; the drift taken at
  // every sample ("energy_error_rel") or at the flight apexes, hop to hop
  // ("energy_error_apex_rel": it leaves out a fixed-step method's bounded transient inside
  // impacts). Returns its CPU time [s] (-1: none) and the run.
  auto fastest_drop = [&drop](const char* error_field, json* run,
                              const char* body = "four_masses") {
    double best = -1;
    *run = {{"found", false}};
    for (const auto& r : drop) {
      if (r["status"] != "completed" || r[error_field].get<double>() > 1e-3) continue;
      if (r.value("body", "four_masses") != body) continue;
      if (best < 0 || r["cpu_s"].get<double>() < best) {
        best = r["cpu_s"];
        *run = r;
      }
    }
    return best;
  };
  json best_run, best_apex_run;
  const double best = fastest_drop("energy_error_rel", &best_run);
  const double best_apex = fastest_drop("energy_error_apex_rel", &best_apex_run);
  h["quad_hopper"]["pronk"] = best_run;
  h["quad_hopper"]["pronk_apex_balance"] = best_apex_run;
  // The same with the body as one rigid body (target: <= 0.5x MuJoCo Euler 1 ms).
  json best_rigid_run;
  const double best_rigid = fastest_drop("energy_error_rel", &best_rigid_run, "rigid");
  h["quad_hopper"]["pronk_rigid"] = best_rigid_run;
  h["quad_hopper"]["rigid_target_over_mujoco_euler_1ms"] = 0.5;
  h["quad_hopper"]["anchor_mujoco_euler_1ms_issue4_s"] = 0.041;
  if (mujoco.value("available", false)) {
    for (const auto& r : mujoco["runs"]) {
      if (r["integrator"] == "Euler" && r["timestep"].get<double>() == 1e-3) {
        h["quad_hopper"]["mujoco_euler_1ms"] = r;
        if (best > 0) {
          // Same simulated time on both sides (the peer scales to 10 s).
          const double pronk_per_s = best / best_run["t_end"].get<double>();
          h["quad_hopper"]["pronk_over_mujoco_euler_1ms"] =
              pronk_per_s / r["cost_per_sim_s"].get<double>();
        }
        if (best_rigid > 0) {
          h["quad_hopper"]["pronk_rigid_over_mujoco_euler_1ms"] =
              best_rigid / best_rigid_run["t_end"].get<double>() /
              r["cost_per_sim_s"].get<double>();
        }
        if (best_apex > 0) {
          h["quad_hopper"]["pronk_apex_balance_over_mujoco_euler_1ms"] =
              best_apex / best_apex_run["t_end"].get<double>() / r["cost_per_sim_s"].get<double>();
        }
      }
    }
  }
  return h;
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return b;
}

std::string machine() {
  std::string cpu = "unknown CPU";
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  return cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

void progress(const BenchArgs& a, const std::string& what) {
  // One line per stage on a terminal (SPEC 8: progress off when not a TTY or --quiet).
  if (!a.quiet && isatty(STDERR_FILENO)) std::fprintf(stderr, "bench: %s\n", what.c_str());
}

}  // namespace

int run_bench(const BenchArgs& args) {
  bench::BenchConfig c;
  c.quick = args.quick;
  c.repeat = args.repeat > 0 ? args.repeat : (args.quick ? 1 : 3);
  c.studies_dir = args.studies_dir.empty() ? PRONK_STUDIES_DIR : args.studies_dir;
  if (!std::filesystem::is_regular_file(c.studies_dir + "/scenes/case3_legged_pulse.json")) {
    throw io::InputError(c.studies_dir, "",
                         "a studies/ directory with scenes/case3_legged_pulse.json",
                         "no such scene (pass --studies DIR)");
  }
  if (args.out_dir.empty()) throw io::InputError("--out", "", "a directory", "an empty path");
  try {
    io::make_directories(args.out_dir);
  } catch (const std::exception& e) {
    throw io::InputError("--out", "", "a directory pronk can create", e.what());
  }
  const auto t0 = std::chrono::steady_clock::now();

  progress(args, "satellite work-precision");
  const auto sat = bench::satellite_work_precision(c);
  progress(args, "satellite stiffness sweep");
  const auto sweep = bench::satellite_stiffness_sweep(c);
  progress(args, "reduced hopper work-precision");
  const auto hop = bench::hopper_work_precision(c);
  const auto orders = bench::fit_orders(hop);
  progress(args, "fidelity ladder");
  const auto ladder = bench::fidelity_ladder(c);
  progress(args, c.quick ? "fidelity ladder: robustness (reduced rungs)"
                         : "fidelity ladder: robustness (the pseudo-rigid rung takes ~2 min)");
  const auto robustness = bench::ladder_robustness(c);
  progress(args, "quad hopper drop (pseudo-rigid)");
  const json drop = bench::quad_hopper_drop(c);

  bool peer_failed = false;
  json cvode = {{"available", false}, {"reason", "--no-peers"}};
  json mujoco = cvode;
  if (!args.no_peers) {
    progress(args, "peer: SUNDIALS CVODE");
    // CVODE also integrates pronk's quad hopper drop: the same mechanism, from a file.
    const std::string quad = args.out_dir + "/quad_hopper_mechanism.json";
    io::write_file_atomic(quad, bench::quad_hopper_mechanism(c.quick ? 2.0 : 10.0).dump(2) + "\n");
    cvode = run_peer("pronk_peer_cvode", "libsundials-dev", args, c.repeat, &peer_failed,
                     " --mechanism '" + quad + "' --drop 0.15");
    progress(args, "peer: MuJoCo");
    mujoco = run_peer("pronk_peer_mujoco", "libmujoco-dev", args, c.repeat, &peer_failed);
  }

  std::vector<WorkPoint> all = sat;
  all.insert(all.end(), sweep.begin(), sweep.end());
  all.insert(all.end(), hop.begin(), hop.end());
  json doc;
  doc["benchmark"] = "pronk bench";
  doc["version"] = pronk::version();
  doc["commit"] = pronk::git_commit();
  doc["date_utc"] = now_utc();
  doc["machine"] = machine();
  doc["quick"] = c.quick;
  doc["repeat"] = c.repeat;
  doc["work_precision"] = json::array();
  for (const auto& p : all) doc["work_precision"].push_back(to_json(p));
  doc["orders"] = json::array();
  for (const auto& o : orders) {
    doc["orders"].push_back({{"problem", o.problem},
                             {"solver", o.solver},
                             {"error", o.error},
                             {"order", o.order},
                             {"points", o.points}});
  }
  doc["fidelity_ladder"] = json::array();
  for (const auto& p : ladder) doc["fidelity_ladder"].push_back(to_json(p));
  doc["fidelity_robustness"] = to_json(robustness);
  doc["quad_hopper_drop"] = drop;
  doc["peers"]["cvode"] = cvode;
  doc["peers"]["mujoco"] = mujoco;
  doc["headline"] = headline(sat, sweep, drop, cvode, mujoco);
  doc["total_wall_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::string& dir = args.out_dir;
  io::write_file_atomic(dir + "/bench.json", doc.dump(2) + "\n");
  io::write_file_atomic(dir + "/work_precision.csv", work_precision_csv(all));
  io::write_file_atomic(dir + "/fidelity_ladder.csv", ladder_csv(ladder));
  io::write_file_atomic(dir + "/fidelity_robustness.csv", robustness_csv(robustness));

  // Figures.
  auto sat_series = wp_series(sat, "satellite", "omega_final");
  if (cvode.value("available", false)) {
    std::map<std::string, Series> by;
    for (const auto& r : cvode["satellite"]) {
      if (r["status"] != "completed") continue;
      const std::string key = "CVODE BDF (" + r["variant"].get<std::string>() + ")";
      by[key].title = key;
      by[key].xy.push_back({r["cpu_s"].get<double>(), r["omega_final"].get<double>()});
    }
    for (auto& [k, v] : by) sat_series.push_back(v);
  }
  const std::vector<std::pair<std::string, std::string>> figs = {
      {"satellite_work_precision",
       loglog_script("satellite_work_precision",
                     "Satellite (k = 1e6 N/m, 20 s): omega error vs CPU time", "CPU time [s]",
                     "relative omega error at 20 s", sat_series)},
      {"hopper_work_precision",
       loglog_script("hopper_work_precision",
                     "Reduced legged pulse hopper: final CoM error vs CPU time", "CPU time [s]",
                     "final CoM position error [m]", wp_series(hop, "hopper", "final_state"))},
  };
  for (const auto& [name, script] : figs) {
    if (!script.empty()) io::render_figure(dir, name, script);
  }
  if (const std::string script = robustness_script(robustness); !script.empty())
    io::render_figure(dir, "fidelity_robustness", script);
  {  // stiffness sweep: wall time vs k
    std::map<std::string, Series> by;
    for (const auto& p : sweep) {
      if (p.status != "completed") continue;
      const std::string key = p.solver + " (" + p.variant + " norm)";
      by[key].title = key;
      by[key].xy.push_back({p.stiffness, p.cpu_s});
    }
    if (cvode.value("available", false)) {
      for (const auto& r : cvode["stiffness"]) {
        if (r["status"] != "completed") continue;
        const std::string key = "CVODE BDF (" + r["variant"].get<std::string>() + ")";
        by[key].title = key;
        by[key].xy.push_back({r["stiffness"].get<double>(), r["cpu_s"].get<double>()});
      }
    }
    std::vector<Series> s;
    for (auto& [k, v] : by) s.push_back(v);
    const std::string script =
        loglog_script("satellite_stiffness", "Satellite, tol 1e-6: CPU time vs internal stiffness",
                      "internal stiffness [N/m]", "CPU time [s]", s);
    if (!script.empty()) io::render_figure(dir, "satellite_stiffness", script);
  }
  {  // quad hopper drop: energy error vs cost per simulated second, pronk and MuJoCo
    std::map<std::string, Series> by;
    for (const auto& r : drop) {
      if (r["status"] != "completed") continue;
      std::string key = r.value("method", "rodas4") == "verlet"
                            ? std::string("pronk Verlet")
                            : "pronk RODAS4 (" + r["norm"].get<std::string>() + " norm)";
      if (r.value("body", "four_masses") == "rigid") key += ", rigid body";
      by[key].title = key;
      by[key].xy.push_back({r["cost_per_sim_s"].get<double>(),
                            std::max(1e-12, r["energy_error_rel"].get<double>())});
    }
    if (mujoco.value("available", false)) {
      for (const auto& r : mujoco["runs"]) {
        if (r["status"] != "completed") continue;
        const std::string key = "MuJoCo " + r["integrator"].get<std::string>();
        by[key].title = key;
        by[key].xy.push_back({r["cost_per_sim_s"].get<double>(),
                              std::max(1e-12, std::abs(r["total_energy_loss_rel"].get<double>()))});
      }
    }
    std::vector<Series> s;
    for (auto& [k, v] : by) s.push_back(v);
    const std::string script =
        loglog_script("quad_hopper_work_precision", "Quad spring hopper drop: energy error vs cost",
                      "CPU time per simulated second [s/s]", "energy error / drop energy", s);
    if (!script.empty()) io::render_figure(dir, "quad_hopper_work_precision", script);
  }
  {  // fixed-step convergence on the hopper
    std::map<std::string, Series> by;
    for (const auto& p : hop) {
      if (p.problem != "hopper" || p.h <= 0 || p.status != "completed") continue;
      by[p.solver].title = p.solver;
      by[p.solver].xy.push_back({p.h, p.errors.at("final_state")});
    }
    std::vector<Series> s;
    for (auto& [k, v] : by) s.push_back(v);
    const std::string script =
        loglog_script("hopper_convergence", "Fixed-step methods on the hopper: error vs step",
                      "step h [s]", "final CoM position error [m]", s);
    if (!script.empty()) io::render_figure(dir, "hopper_convergence", script);
  }

  if (!args.quiet) {
    const json& h = doc["headline"];
    std::printf("pronk bench%s: %.1f s on %s\n", c.quick ? " --quick" : "",
                doc["total_wall_s"].get<double>(), doc["machine"].get<std::string>().c_str());
    std::printf("%s\n", h.dump(2).c_str());
    std::printf("fidelity ladder, robustness (%ld trials of %g s per duty, map_seed_duty row 0):\n",
                robustness.trials, robustness.trial_duration);
    for (const auto& r : robustness.rungs) {
      if (!r.available) {
        std::printf("  %-12s %s\n", r.model.c_str(), r.note.c_str());
        continue;
      }
      std::string cells;
      for (const auto& x : r.cells) {
        char b[96];
        std::snprintf(b, sizeof b, " %g: %ld/%ld (rho %.3g)", x.duty, x.stabilized, x.trials,
                      x.spectral_radius);
        cells += b;
      }
      std::printf("  %-12s%s; boundary %s %s; disagreements vs pulse %ld\n", r.model.c_str(),
                  cells.c_str(), r.boundary_status.c_str(), fmt(r.boundary).c_str(),
                  r.disagreements_vs_pulse);
    }
    std::printf(
        "outputs in %s/ (bench.json, work_precision.csv, fidelity_ladder.csv, "
        "fidelity_robustness.csv, *.svg)\n",
        dir.c_str());
  }
  return peer_failed ? 1 : 0;
}

}  // namespace pronk::app
