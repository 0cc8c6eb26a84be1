// `pronk reproduce DESIGN.json [--threads N] [--rtol R] [--strict] [--scenarios-only]`:
// re-evaluates a tuned design and reports (a) its per-trial decisions and (b) its recorded
// values, each against what the build may promise (optimize/reproduce.hpp).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct ReproduceArgs {
  std::string design_path;
  int threads = 0;   ///< 0: all hardware threads
  std::string rtol;  ///< as given ("" when not): a plain relative comparison, not the design's
  bool strict = false;
  bool scenarios_only = false;
  long front_index = -1;  ///< >= 0: the file is a pareto.json, reproduce this front design
};

CLI::App* add_reproduce_command(CLI::App& app, ReproduceArgs& args);

/// 0: the decisions are identical and every value within its tolerance; 1: not.
int run_reproduce(const ReproduceArgs& args);

}  // namespace pronk::app
