#include <filesystem>
#include <string>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/design_reader_detail.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize::design_detail {

using nlohmann::json;

namespace {

// A metric name of any model, or an aggregate of one ("cvar(y_error)").
bool any_metric_name(const std::string& k) {
  if (is_metric(k)) return true;
  const size_t open = k.find('(');
  if (open == std::string::npos || k.back() != ')') return false;
  const std::string how = k.substr(0, open);
  return (how == "mean" || how == "worst" || how == "cvar") &&
         is_metric(k.substr(open + 1, k.size() - open - 2));
}

// {"cost", "ok", "metrics"}: an evaluation a staged design records.
void check_evaluation_record(io::JsonReader r, const json& node) {
  r.number("cost");
  required_bool(r, "ok");
  read_numbers(r, node, "metrics", any_metric_name, "a metric name");
  r.finish();
}

// One entry of a staged design's "stages"; returns its name.
std::string check_stage_record(io::JsonReader s, const json& node, const json& stage_doc) {
  const std::string name = required_string(s, "name");
  if (stage_doc.is_object() && stage_doc.value("name", name) != name) {
    throw s.error("name", "\"" + stage_doc.value("name", std::string()) + "\" (the staged study's)",
                  "\"" + name + "\"");
  }
  require(s, "model");
  s.choice_or("model", "", scene::model_names());
  required_string(s, "directory");
  read_numbers(
      s, node, "parameters", [](const std::string&) { return true; }, "");
  s.number("cost");
  s.number("initial_cost");
  read_numbers(s, node, "metrics", any_metric_name, "a metric name");
  require(s, "optimizer");
  s.object("optimizer");  // its fields: the stage's own design.json
  require(s, "stability");
  if (!node.at("stability").is_null()) s.object("stability");
  s.finish();
  return name;
}

// The last stage's own design.json, where its directory beside the staged design holds one:
// every value in it must be the staged design's, which carries the last stage's record. So
// reproducing the staged design reproduces the last stage too, and CTest and
// scripts/reproduce_all.sh run that reproduction once (CMakeLists.txt).
void check_last_stage_file(const std::string& path, const json& design) {
  namespace fs = std::filesystem;
  const json& last = design.at("stages").back();
  const fs::path dir = fs::path(last.at("directory").get<std::string>()).filename();
  const fs::path file = fs::path(path).parent_path() / "stages" / dir / "design.json";
  std::error_code ec;
  if (dir.empty() || !fs::is_regular_file(file, ec)) return;
  const json stage = io::read_json_file(file.string());
  if (!stage.is_object()) {
    throw io::InputError(file.string(), "", "the last stage's design (an object)",
                         io::describe(stage));
  }
  for (const auto& [key, value] : stage.items()) {
    if (!design.contains(key) || design.at(key) != value) {
      throw io::InputError(file.string(), "/" + io::pointer_escape(key),
                           design.contains(key)
                               ? "the staged design's /" + key + " (" + path + ")"
                               : "nothing (the staged design " + path + " has no /" + key + ")",
                           io::describe(value));
    }
  }
}

// A staged study's design: its stages, the fidelity gap and the cross evaluation, with the
// last stage's record the design itself.
}  // namespace

void check_staged_records(io::JsonReader& r, const json& design) {
  const std::string staged = required_string(r, "staged_study");
  require(r, "staged_study_document");
  r.optional("staged_study_document");
  const json& doc = design.at("staged_study_document");
  if (!doc.is_object() || doc.value("name", std::string()) != staged || !doc.contains("stages")) {
    throw r.error("staged_study_document", "the staged study \"" + staged + "\" with its stages",
                  io::describe(doc.is_object() && doc.contains("name") ? doc.at("name") : doc));
  }
  require(r, "stages");
  const json& stages = design.at("stages");
  std::vector<io::JsonReader> readers = r.object_array("stages");
  if (stages.empty() || stages.size() != doc.at("stages").size()) {
    throw r.error("stages",
                  std::to_string(doc.at("stages").size()) + " stages (the staged study's)",
                  std::to_string(stages.size()));
  }
  std::vector<std::string> names;
  for (size_t k = 0; k < stages.size(); ++k) {
    names.push_back(check_stage_record(readers[k], stages[k], doc.at("stages")[k]));
  }
  // The last stage is this design.
  const json& last = stages.back();
  const std::string at = "/stages/" + std::to_string(stages.size() - 1);
  if (last.at("model") != design.at("model")) {
    throw io::InputError(r.file(), at + "/model", io::describe(design.at("model")) + " (/model)",
                         io::describe(last.at("model")));
  }
  for (const char* k : {"cost", "metrics"}) {
    if (last.at(k) != design.at(k)) {
      throw io::InputError(r.file(), at + "/" + k, "the design's /" + std::string(k),
                           io::describe(last.at(k)));
    }
  }
  for (const auto& [name, v] : design.at("parameters").items()) {
    if (!last.at("parameters").contains(name) || last.at("parameters").at(name) != v) {
      throw io::InputError(r.file(), at + "/parameters/" + io::pointer_escape(name),
                           io::describe(v) + " (/parameters/" + name + ")",
                           last.at("parameters").contains(name)
                               ? io::describe(last.at("parameters").at(name))
                               : "nothing");
    }
  }
  check_last_stage_file(r.file(), design);
  require(r, "fidelity_gap");
  io::JsonReader gap = r.object("fidelity_gap");
  if (required_string(gap, "model") != last.at("model").get<std::string>()) {
    throw gap.error("model", io::describe(last.at("model")) + " (the last stage's)",
                    io::describe(design.at("fidelity_gap").at("model")));
  }
  if (required_string(gap, "first_stage") != names.front()) {
    throw gap.error("first_stage", "\"" + names.front() + "\"",
                    io::describe(design.at("fidelity_gap").at("first_stage")));
  }
  for (const char* k : {"first_stage_design", "final_design"}) {
    require(gap, k);
    check_evaluation_record(gap.object(k), design.at("fidelity_gap").at(k));
  }
  gap.finish();
  if (r.has("cross_evaluation")) {
    std::vector<io::JsonReader> rows = r.object_array("cross_evaluation");
    if (rows.size() != names.size()) {
      throw r.error("cross_evaluation", std::to_string(names.size()) + " rows (one per stage)",
                    std::to_string(rows.size()));
    }
    for (size_t i = 0; i < rows.size(); ++i) {
      const json& row = design.at("cross_evaluation")[i];
      if (required_string(rows[i], "design") != names[i]) {
        throw rows[i].error("design", "\"" + names[i] + "\"", io::describe(row.at("design")));
      }
      require(rows[i], "evaluated_by");
      io::JsonReader by = rows[i].object("evaluated_by");
      for (const std::string& n : names) {
        require(by, n);
        check_evaluation_record(by.object(n), row.at("evaluated_by").at(n));
      }
      by.finish();
      rows[i].finish();
    }
  } else {
    r.optional("cross_evaluation");
  }
}

}  // namespace pronk::optimize::design_detail
