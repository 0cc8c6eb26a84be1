#include "app/compare_command.hpp"

#include <algorithm>
#include <cstdio>

#include "app/optimize_command.hpp"
#include "app/view_command.hpp"
#include "io/write/comparison_output.hpp"
#include "optimize/compare.hpp"
#include "optimize/compare_output.hpp"

namespace pronk::app {

namespace {

// "0.491", "1.2e-05": what a table column can hold.
std::string cell(const std::optional<double>& v) {
  if (!v) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", *v);
  return buf;
}

// One set's rows side by side, then each design's outcomes.
void print_set(const io::ComparisonData& c, const io::ComparisonSet& s, int width) {
  std::printf("\n%s: %s\n", s.name.c_str(), s.description.c_str());
  std::printf("  %-26s", "metric");
  for (const auto& d : c.designs) std::printf(" %*s", width, d.label.c_str());
  std::printf("\n");
  for (const io::ComparisonRow& r : io::comparison_rows(c)) {
    if (r.set != s.name) continue;
    std::printf("  %-26s", r.metric.c_str());
    for (const auto& v : r.values) std::printf(" %*s", width, cell(v).c_str());
    std::printf("\n");
  }
  std::printf("  %-26s", "stabilized/completed/fell");
  for (const auto& trials : s.trials) {
    long n[3] = {0, 0, 0};
    for (const io::ComparisonTrial& t : trials) {
      ++n[t.outcome == "stabilized" ? 0 : t.outcome == "completed" ? 1 : 2];
    }
    const std::string text =
        std::to_string(n[0]) + "/" + std::to_string(n[1]) + "/" + std::to_string(n[2]);
    std::printf(" %*s", width, text.c_str());
  }
  std::printf("\n");
}

void print_comparison(const io::ComparisonData& c, const std::string& dir) {
  std::printf("compare: %zu designs on the trials of %s (study %s)%s\n", c.designs.size(),
              c.reference_file.c_str(), c.reference_study.c_str(),
              c.model.empty() ? "" : (", all in the " + c.model + " model").c_str());
  int width = 12;
  for (const auto& d : c.designs) {
    width = std::max(width, static_cast<int>(d.label.size()));
    std::printf("  %s: %s, study %s, scene %s, %s model%s\n", d.label.c_str(), d.file.c_str(),
                d.study.c_str(), d.scene.c_str(), d.model.c_str(),
                d.own_study ? " (its own study's trials: the numbers design.json records)" : "");
  }
  for (auto it = c.sets.rbegin(); it != c.sets.rend(); ++it) print_set(c, *it, width);
  for (const auto& s : c.sets) {
    for (size_t d = 0; d < s.failure.size(); ++d) {
      if (!s.failure[d].empty()) {
        std::printf("\n%s did not run on the %s: %s\n", c.designs[d].label.c_str(), s.name.c_str(),
                    s.failure[d].c_str());
      }
    }
  }
  if (!c.notes.empty()) std::printf("\n");
  for (const std::string& n : c.notes) std::printf("note: %s\n", n.c_str());
  std::printf("\nwrote %s: compare.csv, trials.csv, summary.md, compare.json, runs/*/ (%s)\n",
              dir.c_str(),
              c.playback_set == "nominal"
                  ? "the nominal trial"
                  : (c.playback_set + " trial " + std::to_string(c.playback_index)).c_str());
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Run tuned designs (design.json) side by side on the same trials: the first design's\n"
      "study's scenarios and validation set, objective and constraints, each design with its\n"
      "own scene and parameters. Writes compare.csv, trials.csv, summary.md, report.html and\n"
      "every design's playback of the same trial (runs/<design>/view.html).");
  cmd->add_option("designs", args.designs, "design.json files (at least two)")->required();
  cmd->add_option("--out", args.out_dir, "Output directory (default: out/compare)");
  cmd->add_option(
      "--model", args.model,
      "Run every design in this model (impulse, pulse, pseudo_rigid, mujoco; default: each "
      "in its own study's)");
  cmd->add_option("--set", args.overrides,
                  "Override every design's scene: --set /json/pointer=value (repeatable), after "
                  "its study's own scene_overrides")
      ->type_name("/PTR=VALUE");
  cmd->add_option("--reference", args.reference,
                  "Whose study's trials, objective and constraints every design runs: the "
                  "design's position among the files (default 1)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--trials", args.trials,
                  "Draw this many random validation trials (default: the reference study's)")
      ->check(CLI::Range(1L, 1000000L));
  cmd->add_option("--seed", args.seed,
                  "Draw the random validation trials from this seed (default: the reference "
                  "study's)")
      ->check(CLI::Range(0LL, 9007199254740991LL));
  cmd->add_option("--play", args.play,
                  "The trial every design plays back: nominal (default: the scene undisturbed), "
                  "scenarios:I or validation:I");
  cmd->add_option("--threads", args.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--quiet,-q", args.quiet, "No progress, no table");
  return cmd;
}

int run_compare(const CompareArgs& args) {
  optimize::CompareOptions opt;
  opt.threads = thread_count(args.threads);
  opt.model = args.model;
  opt.scene_overrides = args.overrides;
  opt.reference = args.reference;
  opt.trials = args.trials;
  if (args.seed >= 0) opt.seed = static_cast<std::uint64_t>(args.seed);
  opt.play = args.play;
  opt.progress = optimize::progress_style(args.quiet);
  opt.validate(args.designs.size());  // before reading a design: a bad option is the first error
  const std::string dir = args.out_dir.empty() ? "out/compare" : args.out_dir;
  optimize::check_comparison_directory(dir);
  const optimize::Comparison c = optimize::compare_designs(args.designs, opt);
  const io::ComparisonData data = optimize::write_comparison(dir, c);
  if (!args.quiet) print_comparison(data, dir);
  write_page_after(dir, args.quiet);
  bool failed = false;
  for (const auto& s : data.sets) {
    for (const std::string& f : s.failure) failed = failed || !f.empty();
  }
  return failed ? 1 : 0;
}

}  // namespace pronk::app
