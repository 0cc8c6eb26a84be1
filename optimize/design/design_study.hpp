// `pronk design`: the staged study that turns a robot (body, legs, target gait) into a
// running design, derived from the robot itself. Every number of the study is written out
// (absolute, in the scene's units), so the study is readable and editable and `pronk
// optimize` reruns it. docs/design.md explains each rule.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "optimize/design/design_options.hpp"

namespace pronk::optimize {

/// The design study for the robot `scene_doc` (read from `scene_file`, which error messages
/// name). The study refers to its scene as `scene_ref` (a path relative to the study).
/// Throws io::InputError for a scene that is not a legged robot, or is not a valid scene.
nlohmann::json derive_design_study(const nlohmann::json& scene_doc, const std::string& scene_file,
                                   const std::string& scene_ref, const DesignOptions& options);

}  // namespace pronk::optimize
