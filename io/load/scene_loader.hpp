// Reads robot scenes from JSON with the error discipline of docs/reliability.md and writes
// the resolved scene (every default made explicit) back to JSON.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/load/input_error.hpp"
#include "io/load/json_document.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::io {

/// Builds a scene from a document; `file` names the source in error messages.
scene::Scene parse_scene(const nlohmann::json& doc, const std::string& file);

/// Reads a scene file, applies the overrides, parses it.
scene::Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

/// The resolved scene: every setting explicit; parse_scene(scene_to_json(s))
/// reproduces s exactly.
nlohmann::json scene_to_json(const scene::Scene& s);

/// A pointer written in the scene file's form that the resolved scene (what studies, maps and
/// perturbations bind to) spells otherwise, as a hint for an error message: "; the resolved
/// scene names it /body/inertia_tensor/1/1" for "/body/inertia/1"; empty for any other.
std::string resolved_pointer_hint(const std::string& pointer);

}  // namespace pronk::io
