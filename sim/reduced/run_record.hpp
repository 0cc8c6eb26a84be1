// The records the robot runs share, whatever the model (reduced or full): the stride
// record opened at a touchdown, the fall reasons, the final state and the reason of a
// completed run. Both hybrid models (reduced/simulator.cpp, robot/robot_simulator.cpp) fill
// RunResult through these, so the records read the same in every model.
#pragma once

#include <map>
#include <string>

#include "sim/control/body_state.hpp"
#include "sim/control/stance_planner.hpp"
#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

/// The stride record opened at touchdown number `index` at time t: the body state, the
/// setpoint and what the controller asked for. Counts a limited or infeasible allocation in
/// `warnings`.
StrideRecord open_stride(long index, double t, const control::BodyState& s,
                         const control::StancePlan& plan, const scene::Scene& scene,
                         std::map<std::string, long>& warnings);

/// Closes `current` at the next touchdown t_next (its stride time and duty cycle); t_next < 0:
/// the run ended before it (stride time 0).
void close_stride(StrideRecord& current, double t_next);

/// "CoM fell below H m at t = T s".
std::string fell_low_reason(const scene::Scene& scene, double t);
/// "body tilted past A deg at t = T s".
std::string tilted_reason(const scene::Scene& scene, double t);

/// The run's end: t_end, the final body state, and for a completed run its reason ("reached
/// N strides" or "reached t = T s").
void finish_run(RunResult& r, double t, const control::BodyState& s, long touchdowns,
                const scene::Scene& scene);

}  // namespace pronk::reduced
