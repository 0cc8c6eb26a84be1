// pronk.Scene: a parsed robot scene with the document it came from, so that
// simulate() can apply overrides to the source exactly as the CLI does.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "python/src/bindings.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::python {

struct PyScene {
  scene::Scene scene;
  std::string file;       ///< the path, or "<dict>"
  nlohmann::json source;  ///< the document as given, overrides applied
};

void bind_scene_class(py::module_& m);

}  // namespace pronk::python
