// `pronk compare A/design.json B/design.json... [--out DIR] [--model M] [--reference K]
// [--trials N] [--seed S] [--play TRIAL] [--threads N] [-q]`: tuned designs run side by side
// on the same trials (optimize/compare.hpp); writes compare.csv, trials.csv, summary.md,
// compare.json, every design's playback run (runs/<label>/view.html) and report.html.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct CompareArgs {
  std::vector<std::string> designs;
  std::string out_dir;
  std::string model;
  std::vector<std::string> overrides;  ///< --set, every design's scene
  int reference = 1;
  long trials = 0;
  long long seed = -1;  ///< -1: the reference study's own
  std::string play = "nominal";
  int threads = 0;  ///< 0: all hardware threads
  bool quiet = false;
};

CLI::App* add_compare_command(CLI::App& app, CompareArgs& args);

/// 0: every design ran and the comparison is written; 1: some design's parameters made no
/// valid scene in its model (the comparison is still written, and says so).
int run_compare(const CompareArgs& args);

}  // namespace pronk::app
