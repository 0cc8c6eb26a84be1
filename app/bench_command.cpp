// `pronk bench`: the command line, the order of the groups and peers, and the files it writes.
#include "app/bench_command.hpp"

#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/figures.hpp"
#include "app/bench/report.hpp"
#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/write/atomic_file.hpp"
#include "optimize/progress.hpp"
#include "sim/run/count_text.hpp"

#ifndef PRONK_STUDIES_DIR
#define PRONK_STUDIES_DIR "studies"
#endif

namespace pronk::app {

using bench::BenchResults;
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

void progress(const BenchArgs& a, const std::string& what) {
  // One line per stage, with the time since the first, on a terminal or in a log (not with
  // --quiet). The stages differ too much in cost for an estimate of the time left; within
  // the robustness stage, each rung counts its cells with the time left (BenchConfig).
  static const auto t0 = std::chrono::steady_clock::now();
  if (a.quiet) return;
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "bench: %s (%s elapsed)\n", what.c_str(),
               optimize::format_duration(s).c_str());
}

bench::BenchConfig bench_config(const BenchArgs& args) {
  bench::BenchConfig c;
  c.quick = args.quick;
  c.repeat = args.repeat > 0 ? args.repeat : (args.quick ? 1 : 3);
  c.studies_dir = args.studies_dir.empty() ? PRONK_STUDIES_DIR : args.studies_dir;
  c.progress = optimize::progress_style(args.quiet);
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
              {"date_utc", bench::now_utc()},
              {"machine", bench::machine()},
              {"quick", c.quick},
              {"repeat", c.repeat},
              {"auto_check", bench::auto_check_json(autos)}};
  doc["total_wall_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  io::write_file_atomic(args.out_dir + "/auto_check.json", doc.dump(2) + "\n");
  if (!args.quiet) print_auto_check(autos);
  return 0;
}

void print_bench_summary(const bench::BenchConfig& c, const json& doc,
                         const bench::LadderRobustness& robustness, const std::string& dir) {
  const json& h = doc["headline"];
  std::printf("pronk bench%s: %.1f s on %s\n", c.quick ? " --quick" : "",
              doc["total_wall_s"].get<double>(), doc["machine"].get<std::string>().c_str());
  std::printf("%s\n", h.dump(2).c_str());
  std::printf("fidelity ladder, robustness (%s of %g s per duty, map_seed_duty row 0):\n",
              run::count_text(robustness.trials, "trial").c_str(), robustness.trial_duration);
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
                cells.c_str(), r.boundary_status.c_str(), bench::fmt(r.boundary).c_str(),
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
  json doc = bench::bench_document(c, r, all);
  doc["total_wall_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::string& dir = args.out_dir;
  io::write_file_atomic(dir + "/bench.json", doc.dump(2) + "\n");
  io::write_file_atomic(dir + "/work_precision.csv", bench::work_precision_csv(all));
  io::write_file_atomic(dir + "/fidelity_ladder.csv", bench::ladder_csv(r.ladder));
  io::write_file_atomic(dir + "/fidelity_robustness.csv", bench::robustness_csv(r.robustness));
  bench::write_bench_figures(dir, r);
  if (!args.quiet) {
    print_bench_summary(c, doc, r.robustness, dir);
    print_auto_check(r.autos);
  }
  return r.peer_failed ? 1 : 0;
}

}  // namespace pronk::app