// `pronk simulate SCENE.json [--model impulse|pulse] [--set /ptr=value]... [--out DIR]`
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct SimulateArgs {
  std::string scene_path;
  std::string model;  ///< empty: the scene's own
  std::vector<std::string> overrides;
  std::string out_dir;  ///< empty: out/<scene name>
  bool quiet = false;
};

/// Registers the subcommand; `args` must outlive parsing.
CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args);

/// Runs it: 0 completed, 1 the run fell or diverged. Throws io::InputError on bad input.
int run_simulate(const SimulateArgs& args);

}  // namespace pronk::app
