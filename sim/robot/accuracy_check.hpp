// Whether a completed full-model run kept its energy balance within the scene's accuracy
// (pseudo_rigid.solver.accuracy, 1e-3 of the run's energy scale by default). Auto reruns a
// run that missed it once, tighter, and a rerun can still miss; a named method (verlet at a
// fixed step, say) is never rerun. Either way `completed` alone would hide it: this check
// gives the run the warning a user must see.
#pragma once

#include <map>
#include <string>

#include "sim/robot/robot_simulator.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::robot {

struct AccuracyCheck {
  double drift_relative = 0.0;  ///< largest sampled energy-balance drift / energy scale [-]
  double accuracy = 0.0;        ///< the scene's target [-]
  bool beyond = false;          ///< completed, and the drift exceeded the target
  /// How the run was integrated, for the message: "verlet h = 0.00012 s, named by the scene:
  /// nothing reruns it" or "auto: verlet h = 3.2e-05 s, already rerun once tighter".
  std::string method;
};

/// The check of a full-model run of scene. Runs that fell or diverged get no flag: their
/// status already says they failed.
AccuracyCheck check_accuracy(const scene::Scene& scene, const RobotRunResult& run);

/// Adds the check's warning "energy_beyond_accuracy" (counted once).
void add_accuracy_warning(const AccuracyCheck& check, std::map<std::string, long>* warnings);

/// The terminal line: "energy balance drifted 0.00068 of its scale, beyond the accuracy 0.0001
/// (verlet h = 0.00012 s, named by the scene: nothing reruns it); ...".
std::string accuracy_warning_text(const AccuracyCheck& check);

}  // namespace pronk::robot
