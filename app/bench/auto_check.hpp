// `pronk bench`'s check of "method": "auto" (issue 23, item 4): on every shipped mechanism
// scene (studies/mechanisms, the bench's quad hopper drop) and on pr_running, auto's CPU time
// against the fastest run of a grid of methods and settings that meets the same accuracy,
// per scene, measured in the same run. Accuracy: the run completed and its largest sampled
// energy-balance drift, relative to its energy scale, is at most auto's target (default
// 1e-3). The grid: verlet over steps 2e-3 ... 3.1e-5 s (factors of sqrt 2) without and with
// an energy budget (energy_tol = accuracy / 2 and / 10), and dopri5, rodas4, radau5 and
// cvode_bdf over rtol = atol = 1e-3 ... 1e-9. Each family goes from cheap to expensive and
// stops at its first setting that meets the accuracy, or once a run costs more than 5x the
// best so far (a tighter setting only costs more).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/suite.hpp"

namespace pronk::app::bench {

/// One timed run of a scene.
struct AutoRun {
  std::string method;       ///< auto (what it chose follows), verlet, dopri5, ...
  double h = 0.0;           ///< verlet: h_fixed [s]
  double energy_tol = 0.0;  ///< verlet: energy budget, relative to the energy scale
  double tol = 0.0;         ///< adaptive: rtol = atol
  std::string status;       ///< completed, diverged, fell, ...
  double cpu_s = 0.0;       ///< median CPU time of the running thread, load + run [s]
  long steps = 0, rejected = 0;
  double drift = 0.0;  ///< largest sampled energy-balance drift / energy scale [-]
  bool meets = false;  ///< completed and drift <= the accuracy
};

/// auto against the grid on one scene.
struct AutoCheck {
  std::string scene;      ///< file stem (or "quad_hopper_mechanism")
  std::string kind;       ///< "mechanism" or "robot"
  double t_end = 0.0;     ///< simulated time [s]
  double accuracy = 0.0;  ///< auto's target, the grid's bar
  std::string choice;     ///< auto's one-line reason
  AutoRun auto_run;
  std::vector<AutoRun> grid;
  int best = -1;        ///< index into grid of the fastest run that meets the accuracy; -1 none
  double ratio = 0.0;   ///< auto's CPU / the best's CPU
  bool within = false;  ///< auto meets the accuracy and ratio <= kAutoRatioTarget
};

constexpr double kAutoRatioTarget = 1.5;

/// Runs the check on every scene (--quick: runs shortened to 1 s, pr_running to 0.6 s, and a
/// smaller grid).
std::vector<AutoCheck> auto_check(const BenchConfig& c);

nlohmann::json to_json(const AutoCheck& a);

}  // namespace pronk::app::bench
