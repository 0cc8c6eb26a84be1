// Kill and resume, deterministically: a three-stage study ends at a crash point
// (PRONK_CRASH_AT=N, io/write/crash_point.hpp: std::_Exit as kill -9 would, after half a
// journal line or with a temporary written and not renamed) at 20 points drawn from a
// seeded generator, is resumed each time, and must leave every stage's files whole and
// equal to an uninterrupted run's: the same files (no temporary, no lock, no missing
// figure or directory), the same bytes but for wall times and replay counts.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/write/crash_point.hpp"
#include "tests/cli/cli_support.hpp"

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

// Three cheap stages over the legged robot: impulse, pulse, impulse again.
json three_stage_study() {
  json doc = json::parse(R"({
    "name": "kill_test",
    "parameters": [
      {"name": "kp_roll", "pointer": "/controller/kp/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "bank_kp", "pointer": "/controller/bank/kp", "lower": 0.01, "upper": 0.2}
    ],
    "scenarios": {"duration": 2, "random": {"count": 2, "seed": 4, "tilt_deg": [0, 8]}},
    "objective": [{"metric": "attitude_error"}, {"metric": "y_error"}],
    "stability": false,
    "optimizer": {"algorithm": "LN_BOBYQA", "max_evaluations": 6},
    "stages": [
      {"name": "impulse", "model": "impulse"},
      {"name": "pulse", "model": "pulse", "optimizer": {"algorithm": "LN_COBYLA", "max_evaluations": 5}},
      {"name": "again", "model": "impulse"}
    ]
  })");
  doc["scene"] = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case3_legged_pulse.json";
  return doc;
}

// pronk with PRONK_CRASH_AT set (or unset for n < 0).
Run pronk_crashing_at(const TempDir& d, long n, const std::vector<std::string>& args) {
  if (n >= 0)
    ::setenv("PRONK_CRASH_AT", std::to_string(n).c_str(), 1);
  else
    ::unsetenv("PRONK_CRASH_AT");
  Run r = cli_support::pronk(d, args);
  ::unsetenv("PRONK_CRASH_AT");
  return r;
}

// Every file under `dir`, relative.
std::set<std::string> files_under(const std::string& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.insert(fs::relative(e.path(), dir).string());
  return out;
}

// A file's content with what differs between two runs of one study taken out: wall times
// (design.json, summary.md, timings.csv's time columns) and the count of replayed
// evaluations (summary.md).
std::string comparable(const std::string& path) {
  const std::string text = slurp(path);
  const std::string name = fs::path(path).filename().string();
  // Wall times, wherever a design, a stage's design or a page carries them.
  static const std::regex wall_time("\"wall_time_s\": ?[-+.e0-9]+");
  if (fs::path(path).extension() == ".json" || fs::path(path).extension() == ".html")
    return std::regex_replace(text, wall_time, "\"wall_time_s\":T");
  if (name == "summary.md") {
    static const std::regex wall("wall time [-+.e0-9]+ s"), replayed("[0-9]+ replayed");
    return std::regex_replace(std::regex_replace(text, wall, "wall time T s"), replayed,
                              "R replayed");
  }
  if (name == "timings.csv") {  // index, simulations, strides
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);) {
      std::vector<std::string> f;
      std::istringstream cells(line);
      for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
      REQUIRE(f.size() == 5);
      out += f[0] + "," + f[3] + "," + f[4] + "\n";
    }
    return out;
  }
  return text;
}

}  // namespace

TEST_CASE("a three-stage study killed at 20 seeded points resumes to the uninterrupted files",
          "[cli][optimize][journal][stages]") {
  // Each run in a directory of its own, all writing to "out": the same paths in every file.
  const std::vector<std::string> run = {"optimize", "study.json", "--threads", "1",
                                        "-q",       "--out",      "out"};
  std::vector<std::string> resume = run;
  resume.push_back("--resume");
  // The uninterrupted run, counting its crash points.
  TempDir ref("kill");
  write_file(ref / "study.json", three_stage_study().dump());
  const Run counted = pronk_crashing_at(ref, 0, run);
  INFO(counted.err);
  REQUIRE(counted.code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(counted.err, m, std::regex("pronk: crash points: ([0-9]+)")));
  const long points = std::stol(m[1]);
  REQUIRE(points > 60);  // journal lines of three stages and every result file
  const std::set<std::string> ref_files = files_under(ref / "out");
  for (const char* f :
       {"design.json", "summary.md", "stages/1_impulse/summary.md",
        "stages/1_impulse/initial/trajectory.csv", "stages/3_again/tuned/summary.json",
        "stages/2_pulse/timings.csv", "stages/2_pulse/stage_complete.json"})
    CHECK(ref_files.count(f) == 1);

  std::mt19937_64 rng(34);
  std::uniform_int_distribution<long> point(1, points);
  for (int k = 0; k < 20; ++k) {
    const long n = point(rng);
    INFO("killed at crash point " << n << " of " << points);
    TempDir d("kill");
    write_file(d / "study.json", three_stage_study().dump());
    const Run killed = pronk_crashing_at(d, n, run);
    REQUIRE(killed.code == pronk::io::kCrashExitCode);
    const Run resumed = pronk_crashing_at(d, -1, resume);
    INFO(resumed.err);
    REQUIRE(resumed.code == 0);
    CHECK(files_under(d / "out") == ref_files);
    for (const std::string& f : ref_files) {
      INFO(f);
      CHECK(comparable(d / ("out/" + f)) == comparable(ref / ("out/" + f)));
    }
  }
}
