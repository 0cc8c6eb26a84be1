// What `pronk design` derives a study from besides the robot: the budget, the duty range, the
// disturbances and robot perturbations the design must withstand, the final model and the
// optimizers. Defaults are the acceptance a running design is held to (docs/design.md).
#pragma once

#include <string>

namespace pronk::optimize {

struct DesignOptions {
  std::string final_model = "pseudo_rigid";  ///< "pulse" or "pseudo_rigid"
  long pulse_evaluations = 60;               ///< the pulse stage's budget
  long full_evaluations = 150;               ///< the full-model stage's budget
  /// The full-model stage's optimizer: "cmaes" (pagmo, global) or "bobyqa" (NLopt, local).
  std::string full_optimizer = "bobyqa";
  long population = 12;  ///< the global optimizer's population
  /// Stance fraction of the stride: the pulse stage's bounds and start. The full model's
  /// spring legs run at about 20 % (docs/design.md: every family robot completes its 10 s
  /// at 0.16-0.2 and most fall at 0.12 or 0.3).
  double duty_lo = 0.14, duty_hi = 0.26, duty = 0.2;
  double tilt_deg = 10.0;       ///< largest start tilt [deg]
  double lateral_offset = 0.2;  ///< largest start lateral offset [m]
  double velocity_kick = 0.2;   ///< largest start velocity kick [m/s]
  /// Robot perturbations of the scenarios and the validation (relative half-widths, 0: off;
  /// a range for friction). `tune_nominal`: the tuning scenarios keep the nominal robot (the
  /// validation still perturbs it: the gap to a robust design is what robust design buys).
  bool tune_nominal = false;
  double mass = 0.15, inertia = 0.20, leg_stiffness = 0.15;
  double friction_lo = 0.6, friction_hi = 1.2;
  long scenarios = 16;     ///< tuning trials per evaluation
  long validation = 32;    ///< held-out trials
  double duration = 10.0;  ///< simulated seconds per trial
  long seed = 1;           ///< every draw and the optimizers' seeds derive from it

  /// False with *err = "field: reason" when an option is out of range.
  bool validate(std::string* err) const;
};

}  // namespace pronk::optimize
