// `pronk design SCENE.json --out DIR [options]`: from a robot (body, legs, target gait) to a
// running design. Derives a staged study from the robot (optimize/design/design_study.hpp),
// writes it to DIR/study.json beside a copy of the scene (DIR/scene.json), then runs it as
// `pronk optimize DIR/study.json --out DIR` would: the design, its validation, the summary
// and the report page land in DIR.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "optimize/design/design_options.hpp"

namespace pronk::app {

struct DesignArgs {
  std::string scene_path;
  std::string out_dir;
  optimize::DesignOptions options;
  std::vector<std::string> overrides;  ///< --set on the scene
  std::vector<double> duty, perturb, friction;  ///< as given: LO,HI / MASS,INERTIA,K / LO,HI
  bool study_only = false;  ///< write the study, do not run it
  int threads = 0;
  bool resume = false;
  bool quiet = false;
};

CLI::App* add_design_command(CLI::App& app, DesignArgs& args);

/// 0: the design was made (or, with --study-only, the study written); 1: the run failed or
/// was stopped. Throws io::InputError (exit 2) for bad input.
int run_design(DesignArgs args);

}  // namespace pronk::app
