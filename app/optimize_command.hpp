// `pronk optimize STUDY.json [--threads N] [--resume [--verify [N]]] [--out DIR] [--set
// /ptr=value]...` and `pronk reproduce DESIGN.json [--threads N]`.
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

struct ReproduceArgs {
  std::string design_path;
  int threads = 0;
  double rtol = 1e-6;  ///< tolerance when the build differs from the recording one
};

CLI::App* add_optimize_command(CLI::App& app, OptimizeArgs& args);
CLI::App* add_reproduce_command(CLI::App& app, ReproduceArgs& args);

/// 0: finished (any optimizer status but failure), 1: the optimizer failed or was stopped.
int run_optimize(const OptimizeArgs& args);
/// 0: every recorded metric reproduced, 1: some did not.
int run_reproduce(const ReproduceArgs& args);

}  // namespace pronk::app
