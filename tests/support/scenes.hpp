// Shared test helpers: load the shipped scenes.
#pragma once

#include <string>
#include <vector>

#include "io/load/scene_loader.hpp"

namespace pronk::test {

inline std::string scene_path(const std::string& name) {
  return std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + name + ".json";
}

inline scene::Scene load_shipped(const std::string& name,
                                 const std::vector<std::string>& overrides = {}) {
  return io::load_scene(scene_path(name), overrides);
}

}  // namespace pronk::test
