// Whether a completed run ended where it was asked to: `completed` says only that the robot
// did not fall or diverge. A run that wandered off its setpoint by metres, or never met the
// settle criteria, completes too; these checks give it the warnings a user must see.
#pragma once

#include <map>
#include <string>

#include "sim/reduced/metrics.hpp"
#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

/// A completed run further than this many hop heights from its setpoint is far from it [-].
constexpr double kFarFromSetpointHopHeights = 10.0;

struct SetpointCheck {
  double distance = 0.0;       ///< horizontal distance from the moving setpoint at the end [m]
  double hop_heights = 0.0;    ///< that distance over the hop height [-]
  bool far = false;            ///< completed, and beyond kFarFromSetpointHopHeights hop heights
  bool never_settled = false;  ///< completed without meeting the settle criteria
};

/// The check of a run and its metrics (compute_metrics). A run that fell or diverged gets
/// neither flag: its status already says it failed.
SetpointCheck check_setpoint(const scene::Scene& scene, const RunResult& run,
                             const RunMetrics& metrics);

/// Adds the check's warnings: "far_from_setpoint" and "never_settled", each counted once.
void add_setpoint_warnings(const SetpointCheck& check, std::map<std::string, long>* warnings);

}  // namespace pronk::reduced
