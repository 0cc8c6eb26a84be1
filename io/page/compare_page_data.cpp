// The page data of a comparison directory (`pronk compare`): compare.json (the designs, where
// they came from, the trial played back), compare.csv, trials.csv and each design's run.
#include <algorithm>
#include <filesystem>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/page/csv_table.hpp"
#include "io/page/page_data.hpp"

namespace pronk::io::page {

namespace {

// Numbers of all the designs' playbacks together (a study's pair holds twice 80000).
constexpr long kComparePlaybackCells = 160000;
constexpr long kComparePlaybackMin = 20000;
constexpr long kCompareTableCells = 1L << 40;  // every metric and trial

// A design's run directory as compare.json names it: runs/<label>, nothing else.
std::string comparepage_run(const nlohmann::json& design, const std::string& file) {
  const nlohmann::json& run = design.value("run", nlohmann::json(""));
  if (!run.is_string()) throw InputError(file, "/designs", "a run directory name", "another type");
  const std::string r = run.get<std::string>();
  const std::string label = r.size() > 5 ? r.substr(5) : "";
  const bool ok = r.empty() || (r.rfind("runs/", 0) == 0 && !label.empty() && label != "." &&
                                label != ".." && label.find('/') == std::string::npos);
  if (!ok) throw InputError(file, "/designs", "runs/<label>", "\"" + r + "\"");
  return r;
}

}  // namespace

nlohmann::json comparison_page_data(const std::string& dir) {
  const std::string file = dir + "/compare.json";
  const nlohmann::json meta = read_json_file(file);
  if (!io::holds(meta, "type", "pronk_comparison")) {
    throw InputError(file, "/type", "\"pronk_comparison\"", "something else");
  }
  const nlohmann::json& designs = meta.value("designs", nlohmann::json());
  if (!designs.is_array() || designs.size() < 2) {
    throw InputError(file, "/designs", "an array of at least two designs", "something else");
  }
  nlohmann::json out = {{"kind", "compare"}, {"comparison", meta}};
  out["metrics"] =
      sampled_table_json(read_csv_table(dir + "/compare.csv", true), kCompareTableCells);
  out["trials"] = sampled_table_json(read_csv_table(dir + "/trials.csv", true), kCompareTableCells);
  const long cells =
      std::max(kComparePlaybackMin, kComparePlaybackCells / static_cast<long>(designs.size()));
  out["runs"] = nlohmann::json::array();
  for (const nlohmann::json& d : designs) {
    const std::string run = comparepage_run(d, file);
    std::error_code ec;
    if (run.empty() || !std::filesystem::is_directory(dir + "/" + run, ec)) {
      out["runs"].push_back(nullptr);  // no playback for this design (the summary says why)
    } else {
      out["runs"].push_back(run_page_data(dir + "/" + run, cells));
    }
  }
  return out;
}

}  // namespace pronk::io::page
