// pronk.run_map and pronk.reproduce: the robustness-map engine and the
// reproduction of a tuned design, as `pronk map` and `pronk reproduce` run them.
#include <cmath>
#include <filesystem>

#include "io/load/scene_loader.hpp"
#include "optimize/map/map_runner.hpp"
#include "optimize/map/map_study.hpp"
#include "optimize/reproduce.hpp"
#include "python/src/bindings.hpp"
#include "python/src/gil_probe.hpp"

namespace pronk::python {

namespace {

namespace mp = optimize::map;

// The cells of a map as columns (cells.csv's numbers; one fraction column per model).
py::dict cells_dict(const mp::MapStudy& st, const std::vector<mp::CellSummary>& cells) {
  io::Table t;
  t.columns = {"index", "row", "column", "value0", "value1"};
  for (const auto m : st.models)
    t.columns.push_back("fraction_" + std::string(scene::to_string(m)));
  for (const char* c :
       {"disagreements", "a_only", "b_only", "mean_settle_strides", "spectral_radius", "peak_force",
        "mean_duty", "fell_fraction", "all_stabilized"}) {
    t.columns.push_back(c);
  }
  for (const auto& c : cells) {
    t.data.insert(t.data.end(), {static_cast<double>(c.index), static_cast<double>(c.row),
                                 static_cast<double>(c.column), c.value0, c.value1});
    t.data.insert(t.data.end(), c.fraction.begin(), c.fraction.end());
    t.add_row({static_cast<double>(c.disagreements), static_cast<double>(c.a_only),
               static_cast<double>(c.b_only), c.mean_settle_strides, c.spectral_radius,
               c.peak_force, c.mean_duty, c.fell_fraction, c.all_stabilized ? 1.0 : 0.0});
  }
  return table_to_dict(t);
}

py::dict run_map(const py::handle& path_or_dict, const py::handle& threads, const py::handle& out,
                 const py::handle& overrides, bool resume, bool figures,
                 const py::handle& base_dir) {
  std::string file;
  nlohmann::json doc = document_arg(path_or_dict, &file);
  for (const auto& o : overrides_arg(overrides)) io::apply_override(doc, o);
  std::string dir =
      base_dir.is_none()
          ? (is_path_arg(path_or_dict) ? std::filesystem::path(file).parent_path().string() : "")
          : py::module_::import("os").attr("fspath")(base_dir).cast<std::string>();
  const mp::MapStudy st = mp::parse_map_study(doc, file, dir.empty() ? "." : dir);
  mp::MapRunOptions opt;
  opt.threads = threads_arg(threads);
  opt.resume = resume;
  opt.figures = figures;
  if (!out.is_none())
    opt.out_dir = py::module_::import("os").attr("fspath")(out).cast<std::string>();
  mp::MapOutcome o;
  {
    ReleaseGil nogil;
    o = mp::run_map(st, opt);
  }
  py::list boundaries;
  for (const auto& b : o.boundaries) boundaries.append(to_python(mp::to_json(b)));
  return py::dict(py::arg("status") = o.status, py::arg("reason") = o.reason,
                  py::arg("out_dir") = o.out_dir, py::arg("cells") = cells_dict(st, o.summaries),
                  py::arg("boundaries") = boundaries, py::arg("summary") = to_python(o.summary),
                  py::arg("simulations") = o.simulations, py::arg("wall_time") = o.wall_time);
}

// rtol as the CLI's --rtol takes it: a finite number > 0 (ValueError otherwise).
double rtol_arg(double rtol) {
  if (!(std::isfinite(rtol) && rtol > 0.0)) {
    throw py::value_error("rtol: expected a finite number > 0, found " +
                          py::repr(py::float_(rtol)).cast<std::string>());
  }
  return rtol;
}

py::dict reproduce(const py::handle& design, const py::handle& threads, const py::handle& rtol) {
  std::string file;
  const nlohmann::json doc = document_arg(design, &file);
  optimize::ReproduceOptions opt;
  opt.threads = threads_arg(threads);
  if (!rtol.is_none()) opt.rtol = rtol_arg(rtol.cast<double>());
  optimize::ReproduceReport rep;
  {
    ReleaseGil nogil;
    rep = optimize::reproduce_design(doc, file, opt);
  }
  py::list values, decisions;
  for (const auto& v : rep.values) {
    values.append(py::dict(py::arg("name") = v.name, py::arg("recorded") = v.recorded,
                           py::arg("reproduced") = v.reproduced, py::arg("tolerance") = v.tolerance,
                           py::arg("ok") = v.ok));
  }
  for (const auto& d : rep.decision_differences) {
    decisions.append(
        py::dict(py::arg("set") = d.set, py::arg("index") = d.index,
                 py::arg("name") = d.recorded.name, py::arg("recorded") = d.recorded.describe(),
                 py::arg("reproduced") = d.reproduced.describe(), py::arg("fragile") = d.fragile));
  }
  const char* mode = rep.mode == optimize::CompareMode::kBitIdentical ? "bit-identical"
                     : rep.mode == optimize::CompareMode::kTolerance  ? "tolerance"
                                                                      : "rtol";
  return py::dict(py::arg("reproduced") = rep.reproduced(), py::arg("same_build") = rep.same_build,
                  py::arg("mode") = mode, py::arg("rtol") = rep.rtol,
                  py::arg("mismatches") = rep.mismatches, py::arg("values") = values,
                  py::arg("decisions_recorded") = rep.decisions_recorded,
                  py::arg("decision_mismatches") = rep.decision_mismatches,
                  py::arg("decision_differences") = decisions);
}

}  // namespace

void bind_engines(py::module_& m) {
  m.def("run_map", &run_map, py::arg("path_or_dict"), py::kw_only(), py::arg("threads") = 0,
        py::arg("out") = py::none(), py::arg("overrides") = py::none(), py::arg("resume") = false,
        py::arg("figures") = true, py::arg("base_dir") = py::none(),
        "Runs a map study (\"kind\": \"map\") as `pronk map` does and writes its files to out\n"
        "(default: the study's output). Returns status, reason, out_dir, cells (dict of\n"
        "arrays, cells.csv's numbers), boundaries, summary (summary.json), simulations,\n"
        "wall_time. The GIL is released while it runs.");
  m.def("reproduce", &reproduce, py::arg("design"), py::kw_only(), py::arg("threads") = 0,
        py::arg("rtol") = py::none(),
        "Re-evaluates a design.json (path or dict) of pronk optimize as `pronk reproduce`\n"
        "does: the per-trial decisions must be identical, and every recorded value\n"
        "bit-identical on the recording build, within the design's recorded tolerance on\n"
        "another, or within rtol when given (a finite number > 0). Returns reproduced,\n"
        "same_build, mode, rtol, mismatches, values (name, recorded, reproduced, tolerance,\n"
        "ok), decisions_recorded, decision_mismatches (differences in trials that are not\n"
        "fragile), decision_differences (set, index, name, recorded, reproduced, fragile).");
}

}  // namespace pronk::python
