// Shared test helpers: load the shipped scenes and the scenes kept with the tests.
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

/// A scene kept with the tests, tests/robot/data/NAME.json (e.g. a design's resolved scene).
inline scene::Scene load_test_scene(const std::string& name,
                                    const std::vector<std::string>& overrides = {}) {
  std::string path = PRONK_SOURCE_DIR;  // (+=: GCC 12 warns falsely on string&& + literal)
  path += "/tests/robot/data/";
  path += name;
  path += ".json";
  return io::load_scene(path, overrides);
}

}  // namespace pronk::test
