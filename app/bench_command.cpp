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

#include "app/bench_auto.hpp"
#include "app/bench_headline.hpp"
#include "app/bench_suite.hpp"
#include "io/write/atomic_file.hpp"
#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/write/plot.hpp"

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
      "Measure speed versus accuracy: work-precision of every solver on the\n"
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
  cmd->add_option("--only", args.only,
                  "Run one group only: \"auto\" (method auto against the fastest method at\n"
                  "the same accuracy, per scene) into DIR/auto_check.json")
      ->check(CLI::IsMember({"auto"}));
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
          {"ran_model", p.ran_model},
          {"rhs_evaluations", p.rhs_evaluations},
          {"jacobians", p.jacobians},
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
  // One line per stage on a terminal (progress off when not a TTY or --quiet).
  if (!a.quiet && isatty(STDERR_FILENO)) std::fprintf(stderr, "bench: %s\n", what.c_str());
}

}  // namespace

namespace {

/// Everything the suites and peers measured, in the order they ran.
struct BenchResults {
  std::vector<WorkPoint> sat, sweep, hop;
  std::vector<bench::OrderFit> orders;
  std::vector<FidelityPoint> ladder;
  bench::LadderRobustness robustness;
  json drop;
  std::vector<bench::AutoCheck> autos;
  json cvode, mujoco;
  bool peer_failed = false;
};

bench::BenchConfig bench_config(const BenchArgs& args) {
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
  return c;
}

void run_bench_suites(const BenchArgs& args, const bench::BenchConfig& c, BenchResults* r) {
  progress(args, "satellite work-precision");
  r->sat = bench::satellite_work_precision(c);
  progress(args, "satellite stiffness sweep");
  r->sweep = bench::satellite_stiffness_sweep(c);
  progress(args, "reduced hopper work-precision");
  r->hop = bench::hopper_work_precision(c);
  r->orders = bench::fit_orders(r->hop);
  progress(args, "fidelity ladder");
  r->ladder = bench::fidelity_ladder(c);
  progress(args, c.quick ? "fidelity ladder: robustness (reduced rungs)"
                         : "fidelity ladder: robustness (the pseudo-rigid rung takes ~2 min)");
  r->robustness = bench::ladder_robustness(c);
  progress(args, "quad hopper drop (pseudo-rigid)");
  r->drop = bench::quad_hopper_drop(c);
  progress(args, "method auto against the fastest method per scene");
  r->autos = bench::auto_check(c);
}

void run_bench_peers(const BenchArgs& args, const bench::BenchConfig& c, BenchResults* r) {
  r->cvode = {{"available", false}, {"reason", "--no-peers"}};
  r->mujoco = r->cvode;
  if (args.no_peers) return;
  progress(args, "peer: SUNDIALS CVODE");
  // CVODE also integrates pronk's quad hopper drop: the same mechanism, from a file.
  const std::string quad = args.out_dir + "/quad_hopper_mechanism.json";
  io::write_file_atomic(quad, bench::quad_hopper_mechanism(c.quick ? 2.0 : 10.0).dump(2) + "\n");
  r->cvode = run_peer("pronk_peer_cvode", "libsundials-dev", args, c.repeat, &r->peer_failed,
                      " --mechanism '" + quad + "' --drop 0.15");
  progress(args, "peer: MuJoCo");
  r->mujoco = run_peer("pronk_peer_mujoco", "libmujoco-dev", args, c.repeat, &r->peer_failed);
}

/// bench.json's "auto_check": per scene auto against the fastest run at the same accuracy.
json auto_check_json(const std::vector<bench::AutoCheck>& autos) {
  json j = {{"target_ratio", bench::kAutoRatioTarget}, {"scenes", json::array()}};
  bool all = !autos.empty();
  for (const auto& a : autos) {
    j["scenes"].push_back(bench::to_json(a));
    all = all && a.within;
  }
  j["all_within"] = all;
  return j;
}

void print_auto_check(const std::vector<bench::AutoCheck>& autos) {
  std::printf("method auto: CPU / the fastest setting meeting the same accuracy (target <= %g):\n",
              bench::kAutoRatioTarget);
  for (const auto& a : autos) {
    std::string best = "none";
    if (a.best >= 0) {
      const bench::AutoRun& b = a.grid[static_cast<size_t>(a.best)];
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s h %g et %g tol %g: %.4g s, drift %.2g", b.method.c_str(),
                    b.h, b.energy_tol, b.tol, b.cpu_s, b.drift);
      best = buf;
    }
    std::printf("  %-22s %5.2fx %s  auto %.4g s, drift %.2g (%s); best %s\n", a.scene.c_str(),
                a.ratio, a.within ? "ok  " : "MISS", a.auto_run.cpu_s, a.auto_run.drift,
                a.choice.c_str(), best.c_str());
  }
}

/// `pronk bench --only auto`.
int run_auto_only(const BenchArgs& args, const bench::BenchConfig& c) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<bench::AutoCheck> autos = bench::auto_check(c);
  json doc = {{"benchmark", "pronk bench --only auto"},
              {"commit", pronk::git_commit()},
              {"date_utc", now_utc()},
              {"machine", machine()},
              {"quick", c.quick},
              {"repeat", c.repeat},
              {"auto_check", auto_check_json(autos)}};
  doc["total_wall_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_file_atomic(args.out_dir + "/auto_check.json", doc.dump(2) + "\n");
  if (!args.quiet) print_auto_check(autos);
  return 0;
}

/// bench.json without its total wall time.
json bench_document(const bench::BenchConfig& c, const BenchResults& r,
                    const std::vector<WorkPoint>& all) {
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
  for (const auto& o : r.orders) {
    doc["orders"].push_back({{"problem", o.problem},
                             {"solver", o.solver},
                             {"error", o.error},
                             {"order", o.order},
                             {"points", o.points}});
  }
  doc["fidelity_ladder"] = json::array();
  for (const auto& p : r.ladder) doc["fidelity_ladder"].push_back(to_json(p));
  doc["fidelity_robustness"] = to_json(r.robustness);
  doc["quad_hopper_drop"] = r.drop;
  doc["peers"]["cvode"] = r.cvode;
  doc["peers"]["mujoco"] = r.mujoco;
  doc["auto_check"] = auto_check_json(r.autos);
  doc["headline"] = headline(r.sat, r.sweep, r.drop, r.cvode, r.mujoco);
  return doc;
}

std::vector<Series> series_list(std::map<std::string, Series>& by) {
  std::vector<Series> s;
  for (auto& [k, v] : by) s.push_back(v);
  return s;
}

/// The work-precision diagrams of the satellite and the hopper.
void write_work_precision_figures(const std::string& dir, const BenchResults& r) {
  auto sat_series = wp_series(r.sat, "satellite", "omega_final");
  if (r.cvode.value("available", false)) {
    std::map<std::string, Series> by;
    for (const auto& x : r.cvode["satellite"]) {
      if (x["status"] != "completed") continue;
      const std::string key = "CVODE BDF (" + x["variant"].get<std::string>() + ")";
      by[key].title = key;
      by[key].xy.push_back({x["cpu_s"].get<double>(), x["omega_final"].get<double>()});
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
                     "final CoM position error [m]", wp_series(r.hop, "hopper", "final_state"))},
  };
  for (const auto& [name, script] : figs) {
    if (!script.empty()) io::render_figure(dir, name, script);
  }
}

/// Stiffness sweep: wall time vs k.
void write_stiffness_figure(const std::string& dir, const BenchResults& r) {
  std::map<std::string, Series> by;
  for (const auto& p : r.sweep) {
    if (p.status != "completed") continue;
    const std::string key = p.solver + " (" + p.variant + " norm)";
    by[key].title = key;
    by[key].xy.push_back({p.stiffness, p.cpu_s});
  }
  if (r.cvode.value("available", false)) {
    for (const auto& x : r.cvode["stiffness"]) {
      if (x["status"] != "completed") continue;
      const std::string key = "CVODE BDF (" + x["variant"].get<std::string>() + ")";
      by[key].title = key;
      by[key].xy.push_back({x["stiffness"].get<double>(), x["cpu_s"].get<double>()});
    }
  }
  const std::string script =
      loglog_script("satellite_stiffness", "Satellite, tol 1e-6: CPU time vs internal stiffness",
                    "internal stiffness [N/m]", "CPU time [s]", series_list(by));
  if (!script.empty()) io::render_figure(dir, "satellite_stiffness", script);
}

/// Quad hopper drop: energy error vs cost per simulated second, pronk and MuJoCo.
void write_drop_figure(const std::string& dir, const BenchResults& r) {
  std::map<std::string, Series> by;
  for (const auto& x : r.drop) {
    if (x["status"] != "completed") continue;
    std::string key = x.value("method", "rodas4") == "verlet"
                          ? std::string("pronk Verlet")
                          : "pronk RODAS4 (" + x["norm"].get<std::string>() + " norm)";
    if (x.value("body", "four_masses") == "rigid") key += ", rigid body";
    by[key].title = key;
    by[key].xy.push_back(
        {x["cost_per_sim_s"].get<double>(), std::max(1e-12, x["energy_error_rel"].get<double>())});
  }
  if (r.mujoco.value("available", false)) {
    for (const auto& x : r.mujoco["runs"]) {
      if (x["status"] != "completed") continue;
      const std::string key = "MuJoCo " + x["integrator"].get<std::string>();
      by[key].title = key;
      by[key].xy.push_back({x["cost_per_sim_s"].get<double>(),
                            std::max(1e-12, std::abs(x["total_energy_loss_rel"].get<double>()))});
    }
  }
  const std::string script = loglog_script(
      "quad_hopper_work_precision", "Quad spring hopper drop: energy error vs cost",
      "CPU time per simulated second [s/s]", "energy error / drop energy", series_list(by));
  if (!script.empty()) io::render_figure(dir, "quad_hopper_work_precision", script);
}

/// Fixed-step convergence on the hopper.
void write_convergence_figure(const std::string& dir, const BenchResults& r) {
  std::map<std::string, Series> by;
  for (const auto& p : r.hop) {
    if (p.problem != "hopper" || p.h <= 0 || p.status != "completed") continue;
    by[p.solver].title = p.solver;
    by[p.solver].xy.push_back({p.h, p.errors.at("final_state")});
  }
  const std::string script =
      loglog_script("hopper_convergence", "Fixed-step methods on the hopper: error vs step",
                    "step h [s]", "final CoM position error [m]", series_list(by));
  if (!script.empty()) io::render_figure(dir, "hopper_convergence", script);
}

void write_bench_figures(const std::string& dir, const BenchResults& r) {
  write_work_precision_figures(dir, r);
  if (const std::string script = robustness_script(r.robustness); !script.empty())
    io::render_figure(dir, "fidelity_robustness", script);
  write_stiffness_figure(dir, r);
  write_drop_figure(dir, r);
  write_convergence_figure(dir, r);
}

void print_bench_summary(const bench::BenchConfig& c, const json& doc,
                         const bench::LadderRobustness& robustness, const std::string& dir) {
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

}  // namespace

int run_bench(const BenchArgs& args) {
  const bench::BenchConfig c = bench_config(args);
  if (args.only == "auto") return run_auto_only(args, c);
  const auto t0 = std::chrono::steady_clock::now();
  BenchResults r;
  run_bench_suites(args, c, &r);
  run_bench_peers(args, c, &r);

  std::vector<WorkPoint> all = r.sat;
  all.insert(all.end(), r.sweep.begin(), r.sweep.end());
  all.insert(all.end(), r.hop.begin(), r.hop.end());
  json doc = bench_document(c, r, all);
  doc["total_wall_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::string& dir = args.out_dir;
  io::write_file_atomic(dir + "/bench.json", doc.dump(2) + "\n");
  io::write_file_atomic(dir + "/work_precision.csv", work_precision_csv(all));
  io::write_file_atomic(dir + "/fidelity_ladder.csv", ladder_csv(r.ladder));
  io::write_file_atomic(dir + "/fidelity_robustness.csv", robustness_csv(r.robustness));
  write_bench_figures(dir, r);
  if (!args.quiet) {
    print_bench_summary(c, doc, r.robustness, dir);
    print_auto_check(r.autos);
  }
  return r.peer_failed ? 1 : 0;
}

}  // namespace pronk::app
