// `pronk optimize STUDY.json [--threads N] [--resume [--verify [N]]] [--out DIR] [--set
// /ptr=value]...`.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/verify_flags.hpp"

namespace pronk::app {

struct OptimizeArgs {
  std::string study_path;
  int threads = 0;  ///< 0: all hardware threads
  bool resume = false;
  VerifyArgs verify;
  std::string out_dir;
  std::vector<std::string> overrides;
  bool quiet = false;
};

CLI::App* add_optimize_command(CLI::App& app, OptimizeArgs& args);

/// 0: finished (any optimizer status but failure), 1: the optimizer failed or was stopped.
int run_optimize(const OptimizeArgs& args);
/// `requested` worker threads, or all hardware threads for 0.
int thread_count(int requested);

}  // namespace pronk::app
