// pronk.Study: the objective API of a study file as a Python callable. The
// evaluator is the C++ one (its scenarios, thread pool and determinism);
// coordinates are physical (each parameter in its own unit) or, with unit=True,
// the optimizer coordinates in [0, 1] the NLopt and Ipopt drivers see.
#include <chrono>
#include <filesystem>
#include <memory>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"
#include "python/src/bindings.hpp"
#include "python/src/gil_probe.hpp"
#include "python/src/scene_object.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::python {

namespace {

class PyStudy {
 public:
  PyStudy(const py::handle& path_or_dict, const py::handle& threads, bool unit,
          const py::handle& overrides, const py::handle& stage, const py::handle& base_dir)
      : threads_(threads_arg(threads)), unit_(unit) {
    std::string file;
    nlohmann::json doc = document_arg(path_or_dict, &file);
    for (const auto& o : overrides_arg(overrides)) io::apply_override(doc, o);
    std::string dir;
    if (!base_dir.is_none()) {
      dir = py::module_::import("os").attr("fspath")(base_dir).cast<std::string>();
    } else if (is_path_arg(path_or_dict)) {
      dir = std::filesystem::path(file).parent_path().string();
    }
    if (dir.empty()) dir = ".";
    study_ = std::make_shared<optimize::Study>(read_study(doc, file, dir, stage));
    optimize::EvaluatorConfig cfg = study_->evaluator;
    cfg.threads = threads_;
    evaluator_ = std::make_shared<optimize::Evaluator>(cfg);
  }

  /// The held-out validation set of the same study, or None.
  py::object validation() const {
    if (!study_->validation) return py::none();
    auto v = std::make_shared<PyStudy>(*this);
    v->evaluator_ =
        std::make_shared<optimize::Evaluator>(optimize::validation_evaluator(*study_, threads_));
    v->is_validation_ = true;
    return py::cast(v);
  }

  const optimize::Study& study() const { return *study_; }
  const std::vector<optimize::Parameter>& params() const { return study_->evaluator.parameters; }
  bool unit() const { return unit_; }
  int threads() const { return threads_; }
  bool is_validation() const { return is_validation_; }
  /// The C++ evaluator's own wall time of the last evaluate() [s] (the bench's reference).
  double last_wall_time = 0.0;
  const optimize::Evaluator& evaluator() const { return *evaluator_; }

  py::array_t<double> lower() const {
    return coords([](const auto& p) { return p.lower; }, 0.0);
  }
  py::array_t<double> upper() const {
    return coords([](const auto& p) { return p.upper; }, 1.0);
  }
  py::array_t<double> initial() const {
    std::vector<double> v;
    for (const auto& p : params()) v.push_back(unit_ ? p.to_unit(p.initial) : p.initial);
    return to_array(v);
  }

  /// Optimizer coordinates of x (in this study's coordinates); ValueError for a bad x.
  std::vector<double> unit_of(const py::handle& x) const {
    std::vector<double> v = vector_arg(x, params().size(), "x");
    if (!unit_) {
      for (size_t i = 0; i < v.size(); ++i) v[i] = params()[i].to_unit(v[i]);
    }
    return v;
  }

 private:
  static optimize::Study read_study(const nlohmann::json& doc, const std::string& file,
                                    const std::string& dir, const py::handle& stage) {
    if (!optimize::is_staged_study(doc)) {
      if (!stage.is_none()) {
        throw io::InputError(file, "/stages", "stages (stage= names one)", "none");
      }
      return optimize::parse_study(doc, file, dir);
    }
    const optimize::StagedStudy st = optimize::parse_staged_study(doc, file, dir);
    std::string names;
    for (size_t k = 0; k < st.stages.size(); ++k) {
      names += (k ? ", " : "") + st.stages[k].name;
      if (!stage.is_none() && st.stages[k].name == stage.cast<std::string>()) {
        std::map<std::string, double> values;
        for (const auto& p : st.parameters) values[p.name] = p.initial;
        return optimize::stage_study(st, k, values);
      }
    }
    throw io::InputError(file, "/stages", "stage= naming one of the stages (" + names + ")",
                         stage.is_none() ? "no stage" : "\"" + stage.cast<std::string>() + "\"");
  }

  template <class F>
  py::array_t<double> coords(F physical, double unit_value) const {
    std::vector<double> v;
    for (const auto& p : params()) v.push_back(unit_ ? unit_value : physical(p));
    return to_array(v);
  }

  std::shared_ptr<const optimize::Study> study_;
  std::shared_ptr<const optimize::Evaluator> evaluator_;
  int threads_ = 1;
  bool unit_ = false;
  bool is_validation_ = false;
};

py::dict metrics_dict(const optimize::Evaluation& e) {
  py::dict d;
  for (const auto& [k, v] : e.aggregated) d[py::str(k)] = v;
  return d;
}

py::tuple evaluate(PyStudy& s, const py::handle& x) {
  const std::vector<double> u = s.unit_of(x);
  optimize::Evaluation e;
  {
    ReleaseGil nogil;
    e = s.evaluator().evaluate_full(u);
  }
  s.last_wall_time = e.wall_time;  // under the GIL again
  return py::make_tuple(e.cost, to_array(e.constraints), metrics_dict(e));
}

py::tuple evaluate_batch(const PyStudy& s, const py::handle& xs) {
  std::vector<std::vector<double>> us;
  for (const auto& x : xs) us.push_back(s.unit_of(x));
  std::vector<optimize::Evaluation> es;
  {
    ReleaseGil nogil;
    es = s.evaluator().evaluate_full_batch(us);
  }
  const auto n = static_cast<py::ssize_t>(es.size());
  const auto m = static_cast<py::ssize_t>(s.study().evaluator.constraints.size());
  py::array_t<double> cost(n), cons({n, m});
  py::list metrics;
  for (py::ssize_t i = 0; i < n; ++i) {
    cost.mutable_at(i) = es[i].cost;
    for (py::ssize_t j = 0; j < m; ++j) cons.mutable_at(i, j) = es[i].constraints[j];
    metrics.append(metrics_dict(es[i]));
  }
  return py::make_tuple(cost, cons, metrics);
}

// Everything one evaluation knows: per-scenario outcomes, stability, failure.
py::dict evaluate_full(const PyStudy& s, const py::handle& x) {
  const std::vector<double> u = s.unit_of(x);
  optimize::Evaluation e;
  {
    ReleaseGil nogil;
    e = s.evaluator().evaluate_full(u);
  }
  py::list scenarios;
  for (const auto& o : e.scenarios) {
    py::dict m;
    for (const auto& [k, v] : o.metrics) m[py::str(k)] = v;
    scenarios.append(py::dict(py::arg("name") = o.name, py::arg("status") = o.status,
                              py::arg("reason") = o.reason, py::arg("strides") = o.strides,
                              py::arg("metrics") = m));
  }
  return py::dict(py::arg("ok") = e.ok, py::arg("failure") = e.failure, py::arg("cost") = e.cost,
                  py::arg("constraints") = to_array(e.constraints),
                  py::arg("metrics") = metrics_dict(e), py::arg("unit") = to_array(e.unit),
                  py::arg("values") = to_array(e.values),
                  py::arg("spectral_radius") = e.spectral_radius,
                  py::arg("stability_method") = e.stability_method,
                  py::arg("stability_reason") = e.stability_reason,
                  py::arg("model") = std::string(scene::to_string(e.model)),
                  py::arg("simulations") = e.simulations, py::arg("strides") = e.strides,
                  py::arg("scenarios") = scenarios);
}

PyScene scene_at(const PyStudy& s, const py::handle& x) {
  const std::vector<double> u = s.unit_of(x);
  const auto& cfg = s.study().evaluator;
  PyScene out;
  out.source = optimize::bind_parameters(cfg.scene_doc, cfg.parameters, u);
  out.file = cfg.scene_file;
  out.scene = io::parse_scene(out.source, out.file);
  return out;
}

// Benchmark hook: `repeats` evaluations at x in a C++ loop (no Python between
// them), each timed; the reference Study.evaluate's overhead is measured against.
std::vector<double> time_native(const PyStudy& s, const py::handle& x, int repeats) {
  const std::vector<double> u = s.unit_of(x);
  std::vector<double> seconds;
  ReleaseGil nogil;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const optimize::Evaluation e = s.evaluator().evaluate_full(u);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!e.ok) break;
  }
  return seconds;
}

}  // namespace

void bind_study(py::module_& m) {
  py::class_<PyStudy, std::shared_ptr<PyStudy>>(
      m, "Study",
      "The objective of a study file (pronk optimize's format): names, lower, upper, initial,\n"
      "evaluate(x) -> (cost, constraints, metrics), evaluate_batch(X). Constraints are\n"
      "feasible when <= 0. Coordinates are physical, or the optimizer's [0, 1] with unit=True.\n"
      "threads: workers of the C++ thread pool (0: all cores); results never depend on it.\n"
      "A staged study needs stage=NAME (that stage, from the study's initial values).")
      .def(py::init<const py::handle&, const py::handle&, bool, const py::handle&,
                    const py::handle&, const py::handle&>(),
           py::arg("path_or_dict"), py::kw_only(), py::arg("threads") = 0, py::arg("unit") = false,
           py::arg("overrides") = py::none(), py::arg("stage") = py::none(),
           py::arg("base_dir") = py::none())
      .def_property_readonly("name", [](const PyStudy& s) { return s.study().name; })
      .def_property_readonly("file", [](const PyStudy& s) { return s.study().file; })
      .def_property_readonly("names",
                             [](const PyStudy& s) { return s.evaluator().variable_names(); })
      .def_property_readonly("log_scale",
                             [](const PyStudy& s) {
                               std::vector<bool> v;
                               for (const auto& p : s.params()) v.push_back(p.log_scale);
                               return v;
                             })
      .def_property_readonly("lower", &PyStudy::lower)
      .def_property_readonly("upper", &PyStudy::upper)
      .def_property_readonly("initial", &PyStudy::initial)
      .def_property_readonly("constraint_names",
                             [](const PyStudy& s) { return s.evaluator().constraint_names(); })
      .def_property_readonly("unit", &PyStudy::unit)
      .def_property_readonly("threads", &PyStudy::threads)
      .def_property_readonly("is_validation", &PyStudy::is_validation)
      .def_property_readonly(
          "scenarios",
          [](const PyStudy& s) { return s.evaluator().config().scenarios.scenarios.size(); })
      .def_property_readonly("document",
                             [](const PyStudy& s) { return to_python(s.study().document); })
      .def(
          "to_unit",
          [](const PyStudy& s, const py::handle& x) {
            std::vector<double> v = vector_arg(x, s.params().size(), "x");
            for (size_t i = 0; i < v.size(); ++i) v[i] = s.params()[i].to_unit(v[i]);
            return to_array(v);
          },
          "Physical values -> optimizer coordinates in [0, 1] (clamped).")
      .def(
          "from_unit",
          [](const PyStudy& s, const py::handle& u) {
            return to_array(
                optimize::physical_values(s.params(), vector_arg(u, s.params().size(), "u")));
          },
          "Optimizer coordinates -> physical values.")
      .def("evaluate", &evaluate, py::arg("x"),
           "(cost, constraints array, metrics dict) at x. A point that makes an invalid scene\n"
           "gets the failure cost and violated constraints, with empty metrics (see\n"
           "evaluate_full for why). The GIL is released while evaluating.")
      .def("evaluate_batch", &evaluate_batch, py::arg("X"),
           "Evaluates the rows of X in parallel over the thread pool: (costs (n,),\n"
           "constraints (n, m), list of metrics dicts); the same numbers as evaluate.")
      .def("evaluate_full", &evaluate_full, py::arg("x"),
           "The whole evaluation as a dict: ok, failure, cost, constraints, metrics, unit,\n"
           "values, spectral_radius, stability_method, model, scenarios (per-scenario\n"
           "name, status, reason, strides, metrics).")
      .def(
          "__call__", [](PyStudy& s, const py::handle& x) { return evaluate(s, x); }, py::arg("x"))
      .def_readonly("last_wall_time", &PyStudy::last_wall_time,
                    "Seconds the C++ evaluator took inside the last evaluate() call.")
      .def("validation", &PyStudy::validation,
           "Another Study: the same objective (same parameters, bounds, threads and unit\n"
           "scaling) over the study's held-out validation scenarios instead of its training\n"
           "ones, or None when the study has no validation set. Evaluate the tuned point on\n"
           "it, e.g. study.validation().evaluate_full(x), to see how the design generalizes.")
      .def("scene_at", &scene_at, py::arg("x"),
           "The scene at x (a pronk.Scene, for pronk.simulate).")
      .def("_time_native", &time_native, py::arg("x"), py::arg("repeats"),
           "Benchmark hook: seconds of each of `repeats` evaluations in a C++ loop.")
      .def("__repr__", [](const PyStudy& s) {
        const auto n = [](size_t k) { return static_cast<long>(k); };
        return "<pronk.Study " + s.study().name + ": " +
               run::count_text(n(s.params().size()), "parameter") + ", " +
               run::count_text(n(s.evaluator().config().scenarios.scenarios.size()), "scenario") +
               ", " + run::count_text(s.threads(), "thread") + ">";
      });
}

}  // namespace pronk::python
