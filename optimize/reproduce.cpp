#include "optimize/reproduce.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"
#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"

namespace pronk::optimize {

namespace {

// The design's optimizer coordinates, checked against the study's dimension.
std::vector<double> rp_design_unit(const nlohmann::json& design, const std::string& path,
                                   int dimension) {
  std::vector<double> unit;
  try {
    unit = design.at("unit").get<std::vector<double>>();
  } catch (const nlohmann::json::exception&) {
    throw io::InputError(path, "/unit", "an array of numbers", io::describe(design.at("unit")));
  }
  if (static_cast<int>(unit.size()) != dimension) {
    throw io::InputError(path, "/unit", std::to_string(dimension) + " numbers",
                         std::to_string(unit.size()));
  }
  return unit;
}

// Compares the recorded cost and metrics of `record` with evaluation `e`.
void rp_compare_all(ReproduceReport& rep, const nlohmann::json& record, const Evaluation& e,
                    const std::string& prefix) {
  auto compare = [&](const std::string& name, double recorded, double got) {
    const double diff = std::abs(got - recorded);
    const bool ok =
        rep.same_build ? (got == recorded) : (diff <= rep.rtol * std::abs(recorded) + 1e-12);
    if (!ok) ++rep.mismatches;
    rep.values.push_back({name, recorded, got, ok});
  };
  compare(prefix + "cost", record.at("cost").get<double>(), e.cost);
  for (const auto& [k, v] : record.at("metrics").items()) {
    const auto it = e.aggregated.find(k);
    compare(prefix + k, v.get<double>(), it != e.aggregated.end() ? it->second : NAN);
  }
}

}  // namespace

ReproduceReport reproduce_design(const nlohmann::json& design, const std::string& path, int threads,
                                 double rtol) {
  if (!design.is_object() || design.value("type", "") != "pronk_design") {
    throw io::InputError(
        path, "/type", "\"pronk_design\" (a design.json of pronk optimize)",
        design.is_object() && design.contains("type") ? io::describe(design["type"]) : "nothing");
  }
  for (const char* key : {"study_document", "unit", "metrics", "cost"}) {
    if (!design.contains(key)) {
      throw io::InputError(path, std::string("/") + key, "a recorded value", "nothing");
    }
  }
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const Study study =
      parse_study(design.at("study_document"), path + "#/study_document", dir.empty() ? "." : dir);
  EvaluatorConfig cfg = study.evaluator;
  cfg.threads = threads;
  const Evaluator ev(cfg);
  const std::vector<double> unit = rp_design_unit(design, path, ev.dimension());
  ReproduceReport rep;
  rep.rtol = rtol;
  rep.same_build = design.value("commit", "") == std::string(pronk::git_commit()) &&
                   design.value("compiler", "") == compiler_id();
  rp_compare_all(rep, design, ev.evaluate_full(unit), "");
  if (study.validation && design.contains("validation") && design.at("validation").is_object()) {
    const Evaluator val = validation_evaluator(study, threads);
    rp_compare_all(rep, design.at("validation"), val.evaluate_full(unit), "validation ");
  }
  return rep;
}

}  // namespace pronk::optimize
