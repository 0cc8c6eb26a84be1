// The page data of one run directory (robot or mechanism).
#include <algorithm>
#include <filesystem>
#include <set>

#include "io/load/input_error.hpp"
#include "io/page/csv_table.hpp"
#include "io/page/page_data.hpp"
#include "io/load/scene_loader.hpp"

namespace pronk::io::page {

namespace {

namespace fs = std::filesystem;

bool runpage_exists(const std::string& path) {
  std::error_code ec;
  return fs::exists(path, ec);
}

// The table at `path` with a nondecreasing "t" column first and every `required` column.
CsvTable runpage_table(const std::string& path, const std::set<std::string>& required) {
  CsvTable t = read_csv_table(path);
  if (t.columns.empty() || t.columns[0] != "t") {
    throw InputError(path, "line 1", "a first column \"t\"", "\"" + t.columns[0] + "\"");
  }
  const std::set<std::string> have(t.columns.begin(), t.columns.end());
  for (const std::string& c : required) {
    if (have.count(c) == 0) throw InputError(path, "line 1", "a column \"" + c + "\"", "none");
  }
  const nlohmann::json& time = t.data[0];
  for (size_t r = 1; r < time.size(); ++r) {
    if (time[r].get<double>() < time[r - 1].get<double>()) {
      throw InputError(path, "line " + std::to_string(r + 2) + ", column t",
                       "times that never decrease", std::to_string(time[r].get<double>()));
    }
  }
  return t;
}

nlohmann::json runpage_object(const std::string& path) {
  nlohmann::json j = read_json_file(path);
  if (!j.is_object()) throw InputError(path, "", "a JSON object", j.type_name());
  return j;
}

// The robot's geometry as the page draws it: body mass and inertia, leg hips.
void runpage_check_robot(const nlohmann::json& sc, const std::string& path) {
  const nlohmann::json* body = sc.contains("body") ? &sc["body"] : nullptr;
  if (body == nullptr || !body->is_object() || !body->contains("mass") ||
      !(*body)["mass"].is_number()) {
    throw InputError(path, "/body/mass", "the body's mass", "none");
  }
  if (!body->contains("inertia") && !body->contains("inertia_tensor")) {
    throw InputError(path, "/body", "inertia or inertia_tensor", "neither");
  }
  if (sc.contains("legs") && sc["legs"].value("kind", "") == "legged") {
    const nlohmann::json& hips = sc["legs"].value("hips", nlohmann::json());
    bool ok = hips.is_array();
    for (const auto& h : ok ? hips : nlohmann::json::array()) {
      ok = ok && h.is_array() && h.size() == 3 && h[0].is_number() && h[1].is_number() &&
           h[2].is_number();
    }
    if (!ok) throw InputError(path, "/legs/hips", "an array of [x, y, z] hips", "something else");
  }
}

nlohmann::json runpage_robot(const std::string& dir, const nlohmann::json& scene, long cells) {
  const std::set<std::string> traj = {"x",        "y",         "z",       "vx", "vy", "vz",
                                      "roll_deg", "pitch_deg", "yaw_deg", "wx", "wy", "wz",
                                      "x_d",      "y_d",       "stance",  "Fx", "Fy", "Fz"};
  nlohmann::json out = {{"kind", "robot"}, {"name", scene.value("name", "run")}, {"scene", scene}};
  out["summary"] = runpage_object(dir + "/summary.json");
  out["trajectory"] = sampled_table_json(runpage_table(dir + "/trajectory.csv", traj), cells);
  CsvTable strides = read_csv_table(dir + "/strides.csv", false, true);
  for (const char* c : {"stride", "t_touchdown", "apex_height", "duty_cycle"}) {
    const auto& cols = strides.columns;
    if (std::find(cols.begin(), cols.end(), c) == cols.end()) {
      throw InputError(dir + "/strides.csv", "line 1", std::string("a column \"") + c + "\"",
                       "none");
    }
  }
  out["strides"] = sampled_table_json(strides, 1L << 40);
  for (const char* extra : {"feet", "energy"}) {  // the full model's
    const std::string p = dir + "/" + extra + ".csv";
    if (runpage_exists(p)) out[extra] = sampled_table_json(runpage_table(p, {}), cells / 2);
  }
  return out;
}

nlohmann::json runpage_mechanism(const std::string& dir, const nlohmann::json& scene, long cells) {
  nlohmann::json out = {
      {"kind", "mechanism"}, {"name", scene.value("name", "mechanism")}, {"scene", scene}};
  out["summary"] = runpage_object(dir + "/summary.json");
  CsvTable nodes = runpage_table(dir + "/nodes.csv", {});
  if ((nodes.columns.size() - 1) % 3 != 0 || nodes.columns.size() < 4) {
    throw InputError(dir + "/nodes.csv", "line 1", "t and x, y, z columns of each node",
                     std::to_string(nodes.columns.size()) + " columns");
  }
  out["nodes"] = sampled_table_json(nodes, cells);
  out["bodies"] = sampled_table_json(runpage_table(dir + "/bodies.csv", {}), cells / 4);
  out["energy"] = sampled_table_json(runpage_table(dir + "/energy.csv", {"balance"}), cells / 4);
  return out;
}

}  // namespace

nlohmann::json run_page_data(const std::string& dir, long max_cells) {
  const std::string scene_path = dir + "/scene.resolved.json";
  if (!runpage_exists(scene_path)) {
    throw InputError(scene_path, "", "the resolved scene of a run", "no such file");
  }
  const nlohmann::json scene = runpage_object(scene_path);
  if (scene.value("kind", "") == "mechanism") return runpage_mechanism(dir, scene, max_cells);
  runpage_check_robot(scene, scene_path);
  return runpage_robot(dir, scene, max_cells);
}

}  // namespace pronk::io::page
