#include "python/src/scene_object.hpp"

#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"

namespace pronk::python {

void bind_scene_class(py::module_& m) {
  py::class_<PyScene>(m, "Scene",
                      "A robot scene, checked: name, model, file, resolved() (every default "
                      "explicit, as scene.resolved.json), source (the document given).")
      .def_property_readonly("name", [](const PyScene& s) { return s.scene.name; })
      .def_property_readonly(
          "model", [](const PyScene& s) { return std::string(scene::to_string(s.scene.model)); })
      .def_property_readonly("file", [](const PyScene& s) { return s.file; })
      .def_property_readonly("source", [](const PyScene& s) { return to_python(s.source); })
      .def(
          "resolved", [](const PyScene& s) { return to_python(io::scene_to_json(s.scene)); },
          "The scene with every setting explicit (scene.resolved.json).")
      .def_property_readonly(
          "unused_by_this_model", [](const PyScene& s) { return io::unused_settings(s.scene); },
          "Settings this scene's model ignores (JSON Pointers).")
      .def("__repr__", [](const PyScene& s) {
        return "<pronk.Scene " + s.scene.name + " (" +
               std::string(scene::to_string(s.scene.model)) + ") from " + s.file + ">";
      });
}

}  // namespace pronk::python
