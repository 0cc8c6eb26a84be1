#include "app/optimize_command.hpp"
#include "app/mpi_command.hpp"
#include "app/view_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/moo_study.hpp"
#include "optimize/mpi/evaluation_farm.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::app {

namespace {

std::atomic<bool> g_stop{false};

extern "C" void on_sigint(int) {
  g_stop.store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the process at once
}

}  // namespace

int thread_count(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

CLI::App* add_optimize_command(CLI::App& app, OptimizeArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "optimize",
      "Run an optimization study: tune scene parameters over a scenario set with NLopt or Ipopt.\n"
      "Writes journal.jsonl (every evaluation), history.csv, design.json, summary.md and figures.\n"
      "A study with \"objectives\" and pagmo nsga2, moead or nspso writes pareto.csv and\n"
      "pareto.json instead (docs/pareto.md).");
  cmd->add_option("study", args.study_path, "Study file (JSON)")->required();
  cmd->add_option("--threads", args.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--resume", args.resume, "Continue from the journal in the output directory");
  add_verify_flags(cmd, args.verify);
  cmd->add_option("--out", args.out_dir, "Output directory (default: the study's, results/<name>)");
  cmd->add_option("--set", args.overrides,
                  "Override a study value: --set /json/pointer=value (repeatable), e.g. "
                  "--set /optimizer/max_evaluations=50")
      ->type_name("/PTR=VALUE");
  cmd->add_flag("--quiet,-q", args.quiet, "No progress line, no summary");
  return cmd;
}

namespace {

std::string threads_text(int n) { return run::count_text(n, "thread"); }

// The command's options for a study run; Ctrl-C from here on stops at the next evaluation.
optimize::StudyRunOptions run_options(const OptimizeArgs& args, optimize::JobFarm* farm) {
  optimize::StudyRunOptions opt;
  opt.threads = farm ? 1 : thread_count(args.threads);
  opt.farm = farm;
  opt.resume = args.resume;
  opt.verify = args.verify.sample;
  opt.verify_seed = verify_seed(args.verify, args.resume, args.quiet);
  opt.out_dir = args.out_dir;
  opt.progress = optimize::progress_style(args.quiet);
  opt.stop_flag = &g_stop;
  g_stop.store(false);
  std::signal(SIGINT, on_sigint);
  return opt;
}

// A study with "stages": each stage in its own model, from the previous stage's best.
optimize::StagedStudy load_staged(const OptimizeArgs& args, const nlohmann::json& doc) {
  const std::string dir = std::filesystem::path(args.study_path).parent_path().string();
  return optimize::parse_staged_study(doc, args.study_path, dir.empty() ? "." : dir);
}

int run_staged(const OptimizeArgs& args, const optimize::StagedStudy& study,
               optimize::JobFarm* farm) {
  const optimize::StudyRunOptions opt = run_options(args, farm);
  const optimize::StagedOutcome o = optimize::run_staged_study(study, opt);
  std::signal(SIGINT, SIG_DFL);
  if (!args.quiet && o.pareto) {
    for (size_t k = 0; k + 1 < o.stages.size(); ++k) {
      const auto& s = o.stages[k];
      std::printf("  stage %-16s %-13s cost %.6g -> %.6g%s\n", s.name.c_str(), s.model.c_str(),
                  s.design.value("initial_cost", 0.0), s.design.value("cost", 0.0),
                  s.skipped ? " (finished earlier)" : "");
    }
    if (o.ok) {
      std::printf("%s: last stage %s (%s model) multi-objective: a front of %s, hypervolume "
                  "%.6g, knee %ld\n",
                  study.name.c_str(), o.stages.back().name.c_str(), o.stages.back().model.c_str(),
                  run::count_text(o.front_size, "design").c_str(), o.front_hypervolume, o.knee);
      std::printf("  results: %s/ (pareto.json, pareto.csv, stages/), %s\n", o.out_dir.c_str(),
                  farm ? farm->describe().c_str() : threads_text(opt.threads).c_str());
    }
    return o.ok ? 0 : 1;
  }
  if (o.pareto) return o.ok ? 0 : 1;
  if (!args.quiet) {
    for (const auto& s : o.stages) {
      std::printf("  stage %-16s %-13s cost %.6g -> %.6g%s\n", s.name.c_str(), s.model.c_str(),
                  s.design.value("initial_cost", 0.0), s.design.value("cost", 0.0),
                  s.skipped ? " (finished earlier)" : "");
    }
    if (o.ok) {
      std::printf("%s: fidelity gap in the %s model: first stage's design cost %.6g, final %.6g\n",
                  study.name.c_str(), o.stages.back().model.c_str(), o.gap_first.cost,
                  o.final_best.cost);
      std::printf("  results: %s/ (design.json, summary.md, stages/), %s\n", o.out_dir.c_str(),
                  farm ? farm->describe().c_str() : threads_text(opt.threads).c_str());
    }
  }
  if (o.ok) write_page_after(o.out_dir, args.quiet);
  return o.ok ? 0 : 1;
}

}  // namespace

namespace {

// The study (single or staged) after --set; throws io::InputError.
struct LoadedStudy {
  nlohmann::json doc;
  std::optional<optimize::StagedStudy> staged;
  std::optional<optimize::Study> single;
};

LoadedStudy load_any_study(const OptimizeArgs& args) {
  LoadedStudy l;
  l.doc = io::read_json_file(args.study_path);
  for (const auto& o : args.overrides) io::apply_override(l.doc, o);
  if (optimize::is_staged_study(l.doc))
    l.staged.emplace(load_staged(args, l.doc));
  else
    l.single.emplace(optimize::load_study(args.study_path, args.overrides));
  return l;
}

// A multi-objective study: pareto.csv and pareto.json (docs/pareto.md).
int run_multi_objective(const OptimizeArgs& args, const optimize::Study& study,
                        optimize::JobFarm* farm) {
  const optimize::StudyRunOptions opt = run_options(args, farm);
  const optimize::MooStudyOutcome o = optimize::run_moo_study(study, opt);
  std::signal(SIGINT, SIG_DFL);
  if (!args.quiet) {
    const std::string workers = farm ? farm->describe() : threads_text(opt.threads);
    if (o.stopped) {
      std::printf("%s: stopped after %s (resume with --resume)\n", study.name.c_str(),
                  run::count_text(o.evaluations, "evaluation").c_str());
    } else {
      std::printf("%s: pagmo %s, %s (%ld replayed%s), %ld feasible, %.1f s, %s\n",
                  study.name.c_str(), study.moo->algorithm.c_str(),
                  run::count_text(o.evaluations, "evaluation").c_str(), o.replayed,
                  args.verify.sample >= 0
                      ? (", " + std::to_string(o.verified) + " of them verified").c_str()
                      : "",
                  o.feasible, o.wall_time, workers.c_str());
      std::printf("  front: %s, hypervolume %.6g (first population %.6g), knee %ld\n",
                  run::count_text(static_cast<long>(o.front.size()), "design").c_str(),
                  o.front_hypervolume,
                  o.result.hypervolumes.empty() ? 0.0 : o.result.hypervolumes.front(), o.knee);
      std::printf("  results: %s/ (pareto.csv, pareto.json, summary.md, front/)\n",
                  o.out_dir.c_str());
    }
  }
  if (!o.stopped) write_page_after(o.out_dir, args.quiet);
  return o.stopped ? 1 : 0;
}

int run_single(const OptimizeArgs& args, const optimize::Study& study, optimize::JobFarm* farm) {
  if (study.moo) return run_multi_objective(args, study, farm);
  const optimize::StudyRunOptions opt = run_options(args, farm);
  const optimize::StudyOutcome o = optimize::run_study(study, opt);
  std::signal(SIGINT, SIG_DFL);
  if (!args.quiet) {
    const std::string workers = farm ? farm->describe() : threads_text(opt.threads);
    std::printf("%s: %s\n", study.name.c_str(), o.result.brief_report().c_str());
    std::printf("  cost %.6g -> %.6g (%s), %s (%ld replayed%s), %.1f s, %s\n", o.initial.cost,
                o.best.cost, o.result.best_feasible ? "feasible" : "INFEASIBLE",
                run::count_text(o.result.evaluations, "evaluation").c_str(), o.replayed,
                args.verify.sample >= 0
                    ? (", " + std::to_string(o.verified) + " of them verified").c_str()
                    : "",
                o.wall_time, workers.c_str());
    for (size_t i = 0; i < o.best.values.size(); ++i) {
      std::printf("  %-24s %12.6g -> %12.6g\n", study.evaluator.parameters[i].name.c_str(),
                  o.initial.values[i], o.best.values[i]);
    }
    std::printf("  results: %s/ (design.json, summary.md, history.svg, compare.svg)\n",
                o.out_dir.c_str());
  }
  write_page_after(o.out_dir, args.quiet);
  const auto s = o.result.status;
  return (s == optimize::OptimizerStatus::kFailed || s == optimize::OptimizerStatus::kStopped) ? 1
                                                                                               : 0;
}

int run_loaded(const OptimizeArgs& args, const LoadedStudy& l, optimize::JobFarm* farm) {
  return l.staged ? run_staged(args, *l.staged, farm) : run_single(args, *l.single, farm);
}

#ifdef PRONK_WITH_MPI
// Under mpirun: every rank reads the study (and fails the same way on bad input,
// rank 0 telling); rank 0 runs it with the evaluations' jobs spread over the ranks.
int run_optimize_mpi(const OptimizeArgs& args) {
  namespace mp = optimize::mpi;
  return run_on_mpi_ranks<LoadedStudy>(
      [&] { return load_any_study(args); }, [](const LoadedStudy&) { mp::serve_evaluations(); },
      [&](const mp::MpiSession& session, const LoadedStudy& l) {
        mp::MpiJobFarm farm(session);
        const int rc = run_reporting_errors([&] { return run_loaded(args, l, &farm); });
        farm.release_workers();
        return rc;
      });
}
#endif

}  // namespace

int run_optimize(const OptimizeArgs& args) {
#ifdef PRONK_WITH_MPI
  if (optimize::mpi::mpi_launched()) return run_optimize_mpi(args);
#endif
  // N copies would each run the whole study and write the same journal.
  if (refuse_mpirun_without_mpi()) return 2;
  return run_loaded(args, load_any_study(args), nullptr);
}

}  // namespace pronk::app
