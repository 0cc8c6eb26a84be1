// `pronk sensitivity DESIGN.json`: which numbers a tuned design depends on. Local derivatives
// and elasticities of every objective and metric with respect to every tuned parameter and
// physical number, one-at-a-time swings over their ranges (the tornado chart), and Sobol
// indices over the ranges (optimize/sensitivity/design_sensitivity.hpp, docs/sensitivity.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct SensitivityArgs {
  std::string design_path;
  std::string out;    ///< default: sensitivity/ beside the design
  std::string model;  ///< "" : the study's
  bool validation = false;
  std::string physical = "plant";  ///< "plant" or "design"
  double local_step = 1e-2;
  long samples = 128;
  long bootstrap = 200;
  double default_range = 0.1;
  std::vector<std::string> ranges;  ///< POINTER=REL
  std::vector<std::string> inputs;  ///< --inputs: only these (pointers)
  std::string chart = "cost";
  unsigned long long seed = 1;
  int threads = 0;  ///< 0: all hardware threads
  bool quiet = false;
};

CLI::App* add_sensitivity_command(CLI::App& app, SensitivityArgs& args);

/// 0 on success (also when some evaluations made no valid scene: they are reported).
int run_sensitivity(const SensitivityArgs& args);

}  // namespace pronk::app
