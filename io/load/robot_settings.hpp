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

/// The resolved "pseudo_rigid" object; parse_pseudo_rigid reproduces it.
nlohmann::json pseudo_rigid_to_json(const scene::PseudoRigid& p);

/// Top-level scene settings that `scene.model` accepts but does not use, as
/// JSON Pointers (e.g. "/pseudo_rigid" for the reduced models).
std::vector<std::string> unused_settings(const scene::Scene& scene);

}  // namespace pronk::io
