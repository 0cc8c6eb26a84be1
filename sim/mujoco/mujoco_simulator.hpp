// "model": "mujoco": the full model's robot, controller and run loop with MuJoCo as the engine
// (engine/mujoco_stepper.hpp). Built only when CMake finds MuJoCo (PRONK_HAVE_MUJOCO).
#pragma once

#include "sim/robot/robot_simulator.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::mujoco {

/// Why a build without MuJoCo refuses "model": "mujoco".
inline constexpr const char* kNotBuilt =
    "this pronk was built without MuJoCo: \"model\": \"mujoco\" needs Debian's libmujoco-dev "
    "(bash scripts/setup.sh installs it) and a rebuild";

#ifdef PRONK_HAVE_MUJOCO
/// Runs scene s (its model kMujoco) in MuJoCo: the body rigid whatever pseudo_rigid.body says,
/// MuJoCo's integrator and step from s.mujoco. Throws std::invalid_argument for a robot that
/// cannot be built or that MuJoCo refuses; a MuJoCo warning or a non-finite state ends the run
/// `diverged`, the warning named.
robot::RobotRunResult simulate(const scene::Scene& s, const robot::RobotRunOptions& options);
#endif

}  // namespace pronk::mujoco
