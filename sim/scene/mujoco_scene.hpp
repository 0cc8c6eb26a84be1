// What "model": "mujoco" requires of a robot scene (MuJoCo builds the robot with its feet as
// bodies on the legs' slide joints: sim/mujoco/robot_mjcf.hpp). One place for the loader, the
// map study (which sets each cell's model itself) and the MuJoCo rung.
#pragma once

#include <optional>
#include <string>

#include "sim/scene/scene.hpp"

namespace pronk::scene {

/// Why a scene cannot run in MuJoCo: the setting's JSON Pointer, what MuJoCo needs and what
/// the scene has.
struct MujocoRefusal {
  std::string pointer, expected, found;
};

/// The first setting of s (whatever its "model") that MuJoCo cannot run; none when it can.
std::optional<MujocoRefusal> mujoco_refusal(const Scene& s);

}  // namespace pronk::scene
