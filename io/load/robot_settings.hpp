// The pseudo-rigid section of a robot scene ("pseudo_rigid": {...}): read with
// the loader's error discipline, written back resolved, and the list of scene
// settings a given model does not use (reported once in the summary).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/load/json_reader.hpp"
#include "io/load/scaled_settings.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::io {

/// Reads the "pseudo_rigid" object `r` (raw node `node`) into *out, and records in *given
/// which robot-scaled settings it gave (resolve_scaled_settings applies the rest).
void parse_pseudo_rigid(JsonReader r, const nlohmann::json& node, scene::PseudoRigid* out,
                        GivenSettings* given);

/// The resolved "pseudo_rigid" object; parse_pseudo_rigid reproduces it. Settings added after
/// designs were first recorded (placement_trim_gain, actuator_gain, attitude_sensor_bias_deg)
/// are left out at their defaults, so a recorded study's hash, which covers the resolved
/// scene, stays the same.
nlohmann::json pseudo_rigid_to_json(const scene::PseudoRigid& p);

/// Adds those left-out settings at their defaults to a resolved scene's "pseudo_rigid"
/// object, so that a design parameter or a perturbation can name them.
void add_defaulted_settings(nlohmann::json* resolved_scene);

/// Top-level scene settings that `scene.model` accepts but does not use, as
/// JSON Pointers (e.g. "/pseudo_rigid" for the reduced models).
std::vector<std::string> unused_settings(const scene::Scene& scene);

}  // namespace pronk::io
