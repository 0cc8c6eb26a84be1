#include "app/map_command.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <thread>

#include "app/map_report_text.hpp"
#include "app/mpi_command.hpp"
#include "app/view_command.hpp"
#include "io/load/input_error.hpp"
#include "io/write/atomic_file.hpp"
#include "optimize/map/map_playback.hpp"
#include "optimize/map/map_runner.hpp"
#include "optimize/map/map_study.hpp"
#include "optimize/map/mpi_runner.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::app {

namespace {

std::atomic<bool> g_map_stop{false};

extern "C" void on_map_sigint(int) {
  g_map_stop.store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

int report(const optimize::map::MapStudy& st, const optimize::map::MapOutcome& o,
           const std::string& workers, bool quiet) {
  if (o.status != "completed") {
    std::fprintf(stderr, "pronk map: %s: %s\n", st.name.c_str(), o.reason.c_str());
    return 1;
  }
  // One trial per cell to play in report.html, then the page.
  io::write_file_atomic(o.out_dir + "/playback.json",
                        optimize::map::map_playback_json(st).dump() + "\n");
  if (quiet) {
    write_page_after(o.out_dir, quiet);
    return 0;
  }
  std::printf(
      "%s: %s x %s (%ld computed, %ld from the journal%s), %.1f s on %s\n", st.name.c_str(),
      run::count_text(o.cells, "cell").c_str(), run::count_text(st.trials.count, "trial").c_str(),
      o.cells_computed, o.cells_replayed,
      o.verified > 0 ? (", " + run::count_text(o.verified, "record") + " verified").c_str() : "",
      o.wall_time, workers.c_str());
  const auto& d = o.summary["disagreement"];
  if (st.models.size() > 1) {
    std::printf("  disagreements %s vs %s: %s; %s\n",
                std::string(scene::to_string(st.models[0])).c_str(),
                std::string(scene::to_string(st.models[1])).c_str(),
                run::count_text(o.summary["totals"]["disagreements"].get<long>(), "trial").c_str(),
                disagreement_sentence(d, st.axes[0].name).c_str());
  }
  for (const auto& b : o.boundaries) {
    std::printf("  %s\n", boundary_sentence(b, st.axes[0].name).c_str());
  }
  std::printf(
      "  results: %s/ (cells.csv, trials.csv, boundary.csv, summary.json, playback.json, "
      "fraction.svg, disagreement.svg)\n",
      o.out_dir.c_str());
  write_page_after(o.out_dir, quiet);
  return 0;
}

}  // namespace

CLI::App* add_map_command(CLI::App& app, MapArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "map",
      "Robustness map of a design (\"kind\": \"map\" study): seeded disturbance trials per cell "
      "of\n"
      "a 1-D or 2-D grid, two models compared, the stability boundary bisected per row.\n"
      "Under `mpirun -np N pronk map ...` the cells are spread over the ranks.");
  cmd->add_option("study", args.study_path, "Map study file (JSON)")->required();
  cmd->add_option("--threads", args.threads, "Worker threads (default: all cores; MPI: 1 per rank)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--resume", args.resume, "Continue from the journal in the output directory");
  add_verify_flags(cmd, args.verify);
  cmd->add_option("--out", args.out_dir, "Output directory (default: the study's, results/<name>)");
  cmd->add_option("--set", args.overrides,
                  "Override a study value: --set /json/pointer=value (repeatable), e.g. "
                  "--set /trials/count=4")
      ->type_name("/PTR=VALUE");
  cmd->add_flag("--quiet,-q", args.quiet, "No progress line, no summary");
  return cmd;
}

int run_map_command(const MapArgs& args) {
  namespace m = optimize::map;
  m::MapRunOptions opt;
  opt.resume = args.resume;
  opt.verify = args.verify.sample;
  opt.out_dir = args.out_dir;
  opt.stop_flag = &g_map_stop;
  g_map_stop.store(false);
#ifdef PRONK_WITH_MPI
  if (m::mpi_launched()) {
    return run_on_mpi_ranks<m::MapStudy>(
        [&] { return m::load_map_study(args.study_path, args.overrides); },
        [](const m::MapStudy& st) { m::mpi_serve(st); },
        [&](const m::MpiSession& session, const m::MapStudy& st) {
          m::MpiRunner runner(session);
          opt.runner = &runner;
          opt.progress = optimize::progress_style(args.quiet);
          const int rc = run_reporting_errors([&] {
            opt.verify_seed = verify_seed(args.verify, args.resume, args.quiet);
            std::signal(SIGINT, on_map_sigint);
            const m::MapOutcome o = m::run_map(st, opt);
            std::signal(SIGINT, SIG_DFL);
            return report(st, o, runner.describe(), args.quiet);
          });
          runner.release_workers();
          return rc;
        });
  }
#endif
  // N copies would each compute the whole map and write the same files.
  if (refuse_mpirun_without_mpi()) return 2;
  opt.verify_seed = verify_seed(args.verify, args.resume, args.quiet);
  const m::MapStudy st = m::load_map_study(args.study_path, args.overrides);
  const unsigned hw = std::thread::hardware_concurrency();
  opt.threads = args.threads > 0 ? args.threads : (hw > 0 ? static_cast<int>(hw) : 1);
  opt.progress = optimize::progress_style(args.quiet);
  std::signal(SIGINT, on_map_sigint);
  const m::MapOutcome o = m::run_map(st, opt);
  std::signal(SIGINT, SIG_DFL);
  return report(st, o, std::to_string(opt.threads) + (opt.threads == 1 ? " thread" : " threads"),
                args.quiet);
}

}  // namespace pronk::app
