// pronk.load_scene, pronk.Scene, pronk.simulate and its Result: one run of a
// robot scene in any model, with the numbers `pronk simulate` writes
// (summary.json, trajectory.csv, strides.csv; energy.csv and feet.csv for the
// full model) as dicts and NumPy arrays, from the same functions.
#include "sim/simulate.hpp"
#include "io/load/input_error.hpp"
#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/robot_output.hpp"
#include "io/write/simulation_output.hpp"
#include "python/src/bindings.hpp"
#include "python/src/gil_probe.hpp"
#include "python/src/scene_object.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/reduced/setpoint_check.hpp"
#include "sim/robot/accuracy_check.hpp"

namespace pronk::python {

namespace {

/// What simulate() hands back.
struct PyResult {
  std::string status, reason, model;
  double t_end = 0.0;
  py::dict metrics, summary, trajectory, strides;
  py::object energies = py::none(), feet = py::none();
  PyScene scene;
};

/// The scene's source document with the overrides and the model applied, parsed.
PyScene scene_from_doc(nlohmann::json doc, const std::string& file,
                       const std::vector<std::string>& overrides, const std::string& model) {
  for (const auto& o : overrides) io::apply_override(doc, o);
  if (io::is_mechanism_document(doc)) {
    throw io::InputError(file, "/kind", "a robot scene (mechanism scenes run with pronk simulate)",
                         "\"mechanism\"");
  }
  if (!model.empty()) io::apply_override(doc, "/model=\"" + model + "\"");
  PyScene s;
  s.scene = io::parse_scene(doc, file);
  s.file = file;
  s.source = std::move(doc);
  return s;
}

PyScene load_scene(const py::handle& path_or_dict, const py::handle& overrides) {
  std::string file;
  nlohmann::json doc = document_arg(path_or_dict, &file);
  return scene_from_doc(std::move(doc), file, overrides_arg(overrides), "");
}

// The scene argument of simulate(): a Scene as it is (unless overridden), a path or a dict.
PyScene scene_arg(const py::handle& scene, const py::handle& model, const py::handle& overrides) {
  const std::string m = model.is_none() ? "" : model.cast<std::string>();
  const std::vector<std::string> o = overrides_arg(overrides);
  if (py::isinstance<PyScene>(scene)) {
    const PyScene& s = scene.cast<const PyScene&>();
    if (m.empty() && o.empty()) return s;
    return scene_from_doc(s.source, s.file, o, m);
  }
  std::string file;
  nlohmann::json doc = document_arg(scene, &file);
  return scene_from_doc(std::move(doc), file, o, m);
}

PyResult simulate_scene(const py::handle& scene_obj, const py::handle& model,
                        const py::handle& overrides) {
  PyResult out;
  out.scene = scene_arg(scene_obj, model, overrides);
  const scene::Scene& scene = out.scene.scene;
  RunResult r;
  nlohmann::json summary;
  {
    ReleaseGil nogil;
    try {
      r = simulate(scene);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(out.scene.file, "/pseudo_rigid", "a robot the full model can build",
                           e.what());
    }
    const reduced::RunMetrics metrics = reduced::compute_metrics(scene, r.run);
    // The setpoint check's warnings, as `pronk simulate` writes them (summary.json).
    reduced::add_setpoint_warnings(reduced::check_setpoint(scene, r.run, metrics), &r.run.warnings);
    if (r.full_model()) {
      robot::add_accuracy_warning(robot::check_accuracy(scene, r), &r.run.warnings);
    }
    summary = io::simulation_summary_json(scene, r, metrics);
  }
  out.status = summary.at("status").get<std::string>();
  out.reason = r.run.reason;
  out.model = summary.at("model").get<std::string>();
  out.t_end = r.run.t_end;
  out.summary = to_python(summary);
  out.metrics = out.summary["metrics"];
  out.trajectory = table_to_dict(io::trajectory_table(r.run));
  out.strides = table_to_dict(io::strides_table(r.run));
  if (r.full_model()) {
    out.energies = table_to_dict(io::robot_energy_table(r));
    out.feet = table_to_dict(io::robot_feet_table(r));
  }
  return out;
}

}  // namespace

void bind_simulate(py::module_& m) {
  bind_scene_class(m);
  m.def("load_scene", &load_scene, py::arg("path_or_dict"), py::arg("overrides") = py::none(),
        "Reads a robot scene (a JSON file path or a dict) with the CLI's strict validation;\n"
        "overrides: {\"/json/pointer\": value} or [\"/ptr=value\", ...] (the CLI's --set).\n"
        "Bad input raises pronk.InputError (file, pointer, expected, found).");

  py::class_<PyResult>(m, "Result",
                       "One simulation: status, reason, metrics, summary (= summary.json), "
                       "trajectory and strides (dicts of NumPy arrays, the CSV columns), "
                       "energies and feet (full model; None otherwise), scene.")
      .def_readonly("status", &PyResult::status)
      .def_readonly("reason", &PyResult::reason)
      .def_readonly("model", &PyResult::model)
      .def_readonly("t_end", &PyResult::t_end)
      .def_readonly("metrics", &PyResult::metrics)
      .def_readonly("summary", &PyResult::summary)
      .def_readonly("trajectory", &PyResult::trajectory)
      .def_readonly("strides", &PyResult::strides)
      .def_readonly("energies", &PyResult::energies)
      .def_readonly("feet", &PyResult::feet)
      .def_readonly("scene", &PyResult::scene)
      .def("__repr__", [](const PyResult& r) {
        return "<pronk.Result " + r.scene.scene.name + " (" + r.model + "): " + r.status + ", " +
               r.reason + ">";
      });

  m.def("simulate", &simulate_scene, py::arg("scene"), py::arg("model") = py::none(),
        py::arg("overrides") = py::none(),
        "Simulates a scene (a pronk.Scene, a path or a dict) in its model or in `model`\n"
        "(\"impulse\", \"pulse\", \"pseudo_rigid\"), after the overrides, exactly as\n"
        "`pronk simulate` does (the same numbers, bit for bit). The GIL is released while\n"
        "simulating.");
}

}  // namespace pronk::python
