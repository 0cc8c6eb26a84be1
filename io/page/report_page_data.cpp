// The page data of a study, a staged study or a map directory; the classification of a
// directory.
#include <algorithm>
#include <filesystem>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "io/page/csv_table.hpp"
#include "io/page/page_data.hpp"

namespace pronk::io::page {

namespace {

namespace fs = std::filesystem;

bool reportpage_has(const std::string& path) {
  std::error_code ec;
  return fs::exists(path, ec);
}

// Numbers of a study's first-scenario playbacks (initial and tuned, side by side).
constexpr long kPlaybackCells = 80000;
// History rows are never thinned below this many numbers (every evaluation is a point).
constexpr long kHistoryCells = 1L << 40;

nlohmann::json reportpage_object(const std::string& path) {
  nlohmann::json j = read_json_file(path);
  if (!j.is_object()) throw InputError(path, "", "a JSON object", j.type_name());
  return j;
}

// The design without the scene documents (the page shows results, not inputs).
nlohmann::json reportpage_design(const std::string& dir) {
  nlohmann::json d = reportpage_object(dir + "/design.json");
  for (const char* k : {"scene", "staged_study_document"}) d.erase(k);
  return d;
}

// history.csv and design.json of a study (or a stage), with its initial and tuned runs when
// `playback`.
nlohmann::json reportpage_stage(const std::string& dir, bool playback) {
  const CsvTable h = read_csv_table(dir + "/history.csv", true);
  for (const char* c : {"index", "cost"}) {
    if (std::find(h.columns.begin(), h.columns.end(), c) == h.columns.end()) {
      throw InputError(dir + "/history.csv", "line 1", std::string("a column \"") + c + "\"",
                       "none");
    }
  }
  nlohmann::json out = {{"history", sampled_table_json(h, kHistoryCells)},
                        {"design", reportpage_design(dir)}};
  for (const char* run : {"initial", "tuned"}) {
    if (playback && reportpage_has(dir + "/" + run)) {
      out[run] = run_page_data(dir + "/" + run, kPlaybackCells);
    }
  }
  return out;
}

nlohmann::json reportpage_staged(const std::string& dir) {
  nlohmann::json out = {{"kind", "staged"}, {"design", reportpage_design(dir)}};
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir + "/stages")) {
    if (e.is_directory()) names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) throw InputError(dir + "/stages", "", "one directory per stage", "none");
  out["stages"] = nlohmann::json::array();
  for (const std::string& n : names) {
    // Playbacks of the last stage only: the page would carry one pair per stage otherwise.
    nlohmann::json s = reportpage_stage(dir + "/stages/" + n, n == names.back());
    s["name"] = n;
    out["stages"].push_back(std::move(s));
  }
  return out;
}

nlohmann::json reportpage_map(const std::string& dir) {
  nlohmann::json out = {{"kind", "map"}, {"summary", reportpage_object(dir + "/summary.json")}};
  out["cells"] = sampled_table_json(read_csv_table(dir + "/cells.csv", true), kHistoryCells);
  if (reportpage_has(dir + "/boundary.csv")) {
    out["boundary"] =
        sampled_table_json(read_csv_table(dir + "/boundary.csv", true), kHistoryCells);
  }
  if (reportpage_has(dir + "/playback.json")) {
    out["playback"] = reportpage_object(dir + "/playback.json");
  }
  return out;
}

}  // namespace

DirKind classify_directory(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(dir, "", "a directory written by pronk", "no such directory");
  }
  const auto has = [&](const char* f) { return reportpage_has(dir + "/" + f); };
  if (has("trajectory.csv") || has("nodes.csv") || has("scene.resolved.json")) {
    const nlohmann::json sc = has("scene.resolved.json")
                                  ? reportpage_object(dir + "/scene.resolved.json")
                                  : nlohmann::json::object();
    return sc.value("kind", "") == "mechanism" || (!has("trajectory.csv") && has("nodes.csv"))
               ? DirKind::kMechanismRun
               : DirKind::kRobotRun;
  }
  if (has("cells.csv")) return DirKind::kMap;  // a map has a journal.jsonl too
  if (has("compare.json")) return DirKind::kComparison;
  if (has("pareto.json")) return DirKind::kPareto;
  if (has("stages") && has("design.json")) return DirKind::kStagedStudy;
  if (has("history.csv") || has("journal.jsonl")) return DirKind::kStudy;
  throw InputError(dir, "",
                   "a run, study, map or comparison directory written by pronk (trajectory.csv, "
                   "nodes.csv, history.csv, stages/, cells.csv, compare.json or pareto.json)",
                   "none of them");
}

std::string page_name(DirKind kind) {
  return kind == DirKind::kRobotRun || kind == DirKind::kMechanismRun ? "view" : "report";
}

nlohmann::json page_data(const std::string& dir, DirKind kind) {
  try {
    switch (kind) {
      case DirKind::kRobotRun:
      case DirKind::kMechanismRun:
        return run_page_data(dir);
      case DirKind::kStudy: {
        nlohmann::json s = reportpage_stage(dir, true);
        s["kind"] = "study";
        return s;
      }
      case DirKind::kStagedStudy:
        return reportpage_staged(dir);
      case DirKind::kMap:
        return reportpage_map(dir);
      case DirKind::kComparison:
        return comparison_page_data(dir);
      case DirKind::kPareto:
        return pareto_page_data(dir);
    }
  } catch (const nlohmann::json::exception& e) {
    // A file of the right name whose content is not what pronk writes (a wrong type).
    throw InputError(dir, "", "files as pronk writes them", e.what());
  }
  return nullptr;
}

}  // namespace pronk::io::page
