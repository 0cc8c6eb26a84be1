// End-to-end `pronk compare`: its files (compare.csv, trials.csv, summary.md, compare.json,
// each design's playback run), the same bytes whatever the thread count, the numbers each
// design's design.json records in its column, and bad input as one line (exit 2).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/page/page_data.hpp"
#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

std::string committed(const std::string& dir) {
  return std::string(PRONK_SOURCE_DIR) + "/results/" + dir + "/design.json";
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string f;
  while (std::getline(s, f, ',')) out.push_back(f);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::vector<std::vector<std::string>> csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream s(text);
  std::string line;
  while (std::getline(s, line)) rows.push_back(split(line));
  return rows;
}

// compare.csv as {set/metric: [value per design]}.
std::map<std::string, std::vector<double>> metric_table(const std::string& text) {
  std::map<std::string, std::vector<double>> out;
  const auto rows = csv(text);
  for (size_t i = 1; i < rows.size(); ++i) {
    std::vector<double> v;
    for (size_t c = 2; c < rows[i].size(); ++c) {
      v.push_back(rows[i][c].empty() ? NAN : std::strtod(rows[i][c].c_str(), nullptr));
    }
    out[rows[i][0] + "/" + rows[i][1]] = v;
  }
  return out;
}

// Column `column` of compare.csv against the design's recorded validation values: each within
// the tolerance the design records for it (what `pronk reproduce` accepts on another build;
// on the recording build the numbers are bit-identical, well within it).
void check_recorded(const json& design, const std::map<std::string, std::vector<double>>& table,
                    size_t column) {
  const json& v = design.at("validation");
  const json& tol = design.at("reproduction").at("validation").at("tolerance");
  for (const auto& [k, recorded] : v.at("metrics").items()) {
    const auto it = table.find("validation/" + k);
    if (it == table.end()) continue;  // a mean(m) row equal to m's
    INFO(k);
    CHECK(std::abs(it->second.at(column) - recorded.get<double>()) <=
          tol.at("metrics").at(k).get<double>());
  }
  CHECK(std::abs(table.at("validation/cost").at(column) - v.at("cost").get<double>()) <=
        tol.at("cost").get<double>());
}

}  // namespace

TEST_CASE("compare writes the table, the trials and the playbacks, the same for any thread count",
          "[cli][compare]") {
  TempDir d("compare_cli");
  const std::string a = committed("study4_cobyla"), b = committed("study4_bobyqa");
  Run r = cli_support::pronk(d, {"compare", a, b, "--out", "one", "--threads", "1"});
  REQUIRE(r.code == 0);
  // The terminal: where each design came from, then the validation set side by side.
  CHECK_THAT(r.out, StartsWith("compare: 2 designs on the trials of " + a));
  CHECK_THAT(r.out, Contains("  study4_bobyqa: " + b +
                             ", study study4_bobyqa, scene "
                             "legged_pulse_duty50, pulse model (its own study's trials"));
  CHECK_THAT(r.out, Contains("validation: 64 trials of 20 s (64 random, seed 6402)"));
  CHECK_THAT(r.out, Contains("  stabilized/completed/fell"));
  // The files.
  const std::string table = slurp(d / "one/compare.csv");
  CHECK_THAT(table, StartsWith("set,metric,study4_cobyla,study4_bobyqa\nscenarios,cost,"));
  const auto metrics = metric_table(table);
  check_recorded(json::parse(slurp(a)), metrics, 0);
  check_recorded(json::parse(slurp(b)), metrics, 1);
  const auto trials = csv(slurp(d / "one/trials.csv"));
  REQUIRE(trials.size() == 1 + 16 + 64);
  CHECK(trials[0][0] == "set");
  CHECK(trials[0][3] == "study4_cobyla.outcome");
  CHECK(trials[17][0] == "validation");
  CHECK(trials[17][2] == "random_0");
  for (size_t i = 1; i < trials.size(); ++i) {
    REQUIRE(trials[i].size() == 3 + 2 * 9);
    CHECK((trials[i][3] == "stabilized" || trials[i][3] == "completed" || trials[i][3] == "fell" ||
           trials[i][3] == "diverged"));
  }
  const std::string md = slurp(d / "one/summary.md");
  CHECK_THAT(md, StartsWith("# Comparison of 2 designs\n"));
  CHECK_THAT(md, Contains("[study4_bobyqa](runs/study4_bobyqa/view.html)"));
  const json meta = json::parse(slurp(d / "one/compare.json"));
  CHECK(meta.at("type") == "pronk_comparison");
  CHECK(meta.at("playback").at("set") == "nominal");
  for (const char* run : {"one/runs/study4_cobyla", "one/runs/study4_bobyqa"}) {
    CHECK(std::filesystem::exists(d / (std::string(run) + "/trajectory.csv")));
    CHECK(std::filesystem::exists(d / (std::string(run) + "/summary.json")));
  }
  // Two threads: the same bytes.
  r = cli_support::pronk(d, {"compare", a, b, "--out", "two", "--threads", "2", "-q"});
  REQUIRE(r.code == 0);
  CHECK(r.out.empty());
  CHECK(slurp(d / "two/compare.csv") == table);
  CHECK(slurp(d / "two/trials.csv") == slurp(d / "one/trials.csv"));
  CHECK(slurp(d / "two/runs/study4_bobyqa/trajectory.csv") ==
        slurp(d / "one/runs/study4_bobyqa/trajectory.csv"));
}

TEST_CASE("compare --play, --trials and --seed choose the trials", "[cli][compare]") {
  TempDir d("compare_cli");
  const std::string a = committed("study4_cobyla"), b = committed("study4_ipopt");
  const Run r = cli_support::pronk(d, {"compare", a, b, "--out", "c", "--trials", "5", "--seed",
                                       "11", "--play", "validation:4", "-q"});
  REQUIRE(r.code == 0);
  const auto trials = csv(slurp(d / "c/trials.csv"));
  CHECK(trials.size() == 1 + 16 + 5);
  const json meta = json::parse(slurp(d / "c/compare.json"));
  CHECK(meta.at("playback").at("index") == 4);
  CHECK(meta.at("playback").at("name") == "random_4");
  CHECK(meta.at("designs").at(0).at("own_study") == false);  // its validation set redrawn
  CHECK_THAT(slurp(d / "c/summary.md"), Contains("5 trials of 20 s (5 random, seed 11)"));
  // The page's data, read back from the files: both designs' runs, every trial.
  namespace page = pronk::io::page;
  REQUIRE(page::classify_directory(d / "c") == page::DirKind::kComparison);
  const json data = page::page_data(d / "c", page::DirKind::kComparison);
  CHECK(data.at("kind") == "compare");
  REQUIRE(data.at("runs").size() == 2);
  CHECK(data.at("runs").at(1).at("kind") == "robot");
  CHECK(data.at("trials").at("rows") == 16 + 5);
  // A run directory outside the comparison is refused, not read.
  json bad = meta;
  bad["designs"][0]["run"] = "../c";
  write_file(d / "c/compare.json", bad.dump());
  CHECK_THROWS_AS(page::page_data(d / "c", page::DirKind::kComparison), pronk::io::InputError);
}

TEST_CASE("compare: bad input is one line, exit 2", "[cli][compare][input]") {
  TempDir d("compare_cli");
  const std::string a = committed("study2_legged_pulse_duty50");
  // Fewer than two designs.
  check_bad_input(cli_support::pronk(d, {"compare", a}),
                  "command line: /: expected at least two design.json files to compare, found 1");
  // A missing file.
  check_bad_input(cli_support::pronk(d, {"compare", a, "nope/design.json"}),
                  "nope/design.json: /: expected a readable JSON file, found no such file");
  // A mistyped design: the file, the JSON Pointer, what was expected and what was found.
  json bad = json::parse(slurp(a));
  bad["unit"][2] = "0.5";
  write_file(d / "bad.json", bad.dump());
  check_bad_input(cli_support::pronk(d, {"compare", a, "bad.json"}),
                  "bad.json: /unit/2: expected ");
  // A model that ignores a tuned parameter.
  check_bad_input(cli_support::pronk(d, {"compare", a, a, "--model", "impulse"}),
                  a + "#/study_document (run on the trials of " + a +
                      ", in the impulse model): /parameters/0/pointer: expected a setting the "
                      "impulse model uses");
  // --set reaches every design's scene, through the scene's own checks.
  check_bad_input(cli_support::pronk(d, {"compare", a, a, "--set", "/body/mas=2"}),
                  a + "#/study_document (run on the trials of " + a +
                      ", --set /body/mas=2)#/scene: /body/mas: expected a known key");
  check_bad_input(cli_support::pronk(d, {"compare", a, a, "--model", "full"}),
                  "--model: /: expected impulse, pulse, pseudo_rigid or mujoco, found \"full\"");
  check_bad_input(cli_support::pronk(d, {"compare", a, a, "--play", "scenarios:16"}),
                  "--play: /: expected a trial of the scenarios (0 to 15), found \"scenarios:16\"");
  check_bad_input(cli_support::pronk(d, {"compare", a, a, "--threads", "0"}), "command line: ");
  // A study's directory keeps its summary.md.
  std::filesystem::create_directories(d / "study");
  write_file(d / "study/design.json", "{}");
  check_bad_input(cli_support::pronk(d, {"compare", a, a, "--out", "study"}),
                  "--out: /: expected a new directory or one `pronk compare` wrote");
  CHECK(slurp(d / "study/design.json") == "{}");
}
