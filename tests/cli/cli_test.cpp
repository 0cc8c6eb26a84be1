// End-to-end tests of the pronk executable (PRONK_EXE): help and usage errors,
// exit code 2 with one "FILE: /pointer: expected X, found Y" line for every
// class of bad input, the output files of a good run, determinism and the
// round trip through scene.resolved.json, the pulse model and a fall (exit 1).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kSceneDir = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/";

/// A fresh directory under /tmp, removed with everything in it at scope exit.

json shipped(const std::string& name) { return json::parse(slurp(kSceneDir + name)); }

long count_lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

/// Every number in the document is finite and no value is null.
void check_no_null(const json& j, const std::string& where = "") {
  INFO("at " << (where.empty() ? "/" : where));
  CHECK_FALSE(j.is_null());
  if (j.is_number_float()) CHECK(std::isfinite(j.get<double>()));
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) check_no_null(*it, where + "/" + it.key());
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) check_no_null(j[i], where + "/" + std::to_string(i));
  }
}

/// The CSV has a header and rows of the header's column count; every cell is a finite number.
void check_csv(const std::string& text, size_t min_rows) {
  std::istringstream in(text);
  std::string line;
  REQUIRE(std::getline(in, line));
  const long columns = std::count(line.begin(), line.end(), ',') + 1;
  size_t rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    INFO("row " << rows << ": " << line);
    REQUIRE(std::count(line.begin(), line.end(), ',') + 1 == columns);
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      REQUIRE(end == cell.c_str() + cell.size());
      REQUIRE(std::isfinite(v));
    }
  }
  CHECK(rows >= min_rows);
}

/// One bad scene: how to break a shipped scene and the pointer the error must name.
struct BadCase {
  std::string label;
  std::string base;
  std::function<void(json&)> mutate;
  std::string pointer;
  std::string expected;  ///< a part of the expected text
};

std::vector<BadCase> bad_cases() {
  const std::string c1 = "case1_body_only.json", c2 = "case2_legged_impulse.json";
  return {
      {"unknown top-level key", c1, [](json& d) { d["colour"] = "red"; }, "/colour", "a known key"},
      {"unknown nested key", c2, [](json& d) { d["controller"]["kpp"] = 1; }, "/controller/kpp",
       "a known key"},
      {"unknown solver key", c1, [](json& d) { d["simulation"]["solver"]["rtoll"] = 1e-6; },
       "/simulation/solver/rtoll", "a known key"},
      {"string for a number", c1, [](json& d) { d["body"]["mass"] = "1.5"; }, "/body/mass",
       "a finite number in [1e-06, 1000000]"},
      {"number for a vector", c1, [](json& d) { d["initial"]["position"] = 0.3; },
       "/initial/position", "an array of 3 numbers"},
      {"vector of the wrong length", c1,
       [](json& d) {
         d["initial"]["position"] = {0, 0.3};
       },
       "/initial/position", "an array of 3 numbers"},
      {"negative mass", c1, [](json& d) { d["body"]["mass"] = -1; }, "/body/mass",
       "a finite number in [1e-06, 1000000]"},
      {"hop height 0", c1, [](json& d) { d["controller"]["hop_height"] = 0; },
       "/controller/hop_height", "a finite number > 0"},
      {"energy blow-up factor 0", "case5_pr_hop_height.json",
       [](json& d) { d["pseudo_rigid"]["energy_blowup_factor"] = 0; },
       "/pseudo_rigid/energy_blowup_factor", "a finite number > 0"},
      {"rtol -1", c1, [](json& d) { d["simulation"]["solver"]["rtol"] = -1; },
       "/simulation/solver/rtol", "a finite number > 0"},
      {"max_roll_deg 100", c2, [](json& d) { d["controller"]["bank"]["max_roll_deg"] = 100; },
       "/controller/bank/max_roll_deg", "a finite number in [1e-06, 89]"},
      {"inertia violating the triangle inequality", c1,
       [](json& d) {
         d["body"]["inertia"] = {0.1, 0.1, 0.3};
       },
       "/body/inertia", "principal moments satisfying the triangle inequalities"},
      {"inertia tensor violating the triangle inequality", c1,
       [](json& d) {
         d["body"].erase("inertia");
         d["body"]["inertia_tensor"] = {{0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.3}};
       },
       "/body/inertia_tensor", "principal moments satisfying the triangle inequalities"},
      {"asymmetric inertia tensor", c1,
       [](json& d) {
         d["body"].erase("inertia");
         d["body"]["inertia_tensor"] = {{0.01, 0.001, 0}, {0, 0.01, 0}, {0, 0, 0.015}};
       },
       "/body/inertia_tensor", "a symmetric 3x3 matrix"},
      {"legged without hips", c2, [](json& d) { d["legs"].erase("hips"); }, "/legs/hips",
       "an array of hip positions (legged)"},
      {"disabled leg out of range", c2, [](json& d) { d["legs"]["disabled"] = {4}; },
       "/legs/disabled/0", "integers in [0, 3]"},
      {"disabled leg of a body-only robot", c1, [](json& d) { d["legs"]["disabled"] = {0}; },
       "/legs/disabled/0", "no disabled legs"},
      {"gait group with a bad index", c2,
       [](json& d) {
         d["controller"]["gait"] = {{"kind", "alternate"}, {"groups", {{0, 3}, {1, 7}}}};
       },
       "/controller/gait/groups/1/1", "a distinct leg index in [0, 3]"},
      {"initial CoM below the fall height", c1, [](json& d) { d["initial"]["position"][2] = 0.08; },
       "/initial/position/2", "a CoM height above the fall height 0.1 m"},
      {"both attitude forms", c1,
       [](json& d) {
         d["initial"]["attitude_quaternion"] = {1, 0, 0, 0};
       },
       "/initial/attitude_quaternion", "either attitude_deg or attitude_quaternion"},
  };
}

/// Checks a bad-input run: exit 2, one error line naming file and pointer, no outputs.
void check_bad_input(const Run& r, const std::string& file, const std::string& pointer,
                     const std::string& expected) {
  INFO("stderr: " << r.err);
  CHECK(r.code == 2);
  CHECK(count_lines(r.err) == 1);
  CHECK_THAT(r.err, StartsWith("pronk: error: " + file + ": " + pointer + ": expected "));
  CHECK_THAT(r.err, Contains("expected " + expected));
  CHECK_THAT(r.err, Contains(", found "));
  CHECK(r.out.empty());
}

}  // namespace

TEST_CASE("pronk --help and simulate --help", "[cli]") {
  TempDir dir("cli");
  const Run top = pronk(dir, {"--help"});
  CHECK(top.code == 0);
  CHECK_THAT(top.out, Contains("simulate"));
  CHECK_THAT(top.out, Contains("Exit codes"));
  const Run sim = pronk(dir, {"simulate", "--help"});
  CHECK(sim.code == 0);
  CHECK_THAT(sim.out, Contains("--set"));
  CHECK_THAT(sim.out, Contains("--model"));
  CHECK_THAT(sim.out, Contains("--out"));
}

TEST_CASE("usage errors exit 2", "[cli]") {
  TempDir dir("cli");
  const Run none = pronk(dir, {});
  CHECK(none.code == 2);
  CHECK_THAT(none.err, Contains("subcommand"));
  CHECK(pronk(dir, {"--no-such-option"}).code == 2);
  CHECK(pronk(dir, {"fly"}).code == 2);
  CHECK(pronk(dir, {"simulate"}).code == 2);  // the scene is required
  const std::string scene = kSceneDir + "case1_body_only.json";
  CHECK(pronk(dir, {"simulate", scene, "--bogus"}).code == 2);
  CHECK(pronk(dir, {"simulate", scene, "--model", "spring"}).code == 2);
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("every class of bad scene exits 2 with one error line", "[cli][errors]") {
  TempDir dir("cli");
  for (const BadCase& c : bad_cases()) {
    INFO(c.label);
    json doc = shipped(c.base);
    c.mutate(doc);
    const std::string file = dir / "bad_scene.json";
    write_file(file, doc.dump(2));
    const Run r = pronk(dir, {"simulate", file, "--out", dir / "out", "-q"});
    check_bad_input(r, file, c.pointer, c.expected);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

TEST_CASE("missing files, invalid JSON and overflowing numbers exit 2", "[cli][errors]") {
  TempDir dir("cli");
  SECTION("missing file") {
    const Run r = pronk(dir, {"simulate", "no_such_scene.json"});
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK_THAT(r.err, StartsWith("pronk: error: no_such_scene.json: /: expected a readable"));
  }
  SECTION("invalid JSON syntax") {
    write_file(dir / "broken.json", "{\"body\": {\"mass\": 1.5,}}\n");
    const Run r = pronk(dir, {"simulate", "broken.json"});
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK_THAT(r.err, StartsWith("pronk: error: broken.json: /: expected valid JSON, found "));
  }
  SECTION("a number beyond the double range in the file") {
    write_file(dir / "huge.json", R"({"name": "huge", "body": {"mass": 1e400}})");
    const Run r = pronk(dir, {"simulate", "huge.json"});
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK_THAT(r.err, StartsWith("pronk: error: huge.json: "));
    CHECK_THAT(r.err, Contains("1e400"));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  SECTION("a number beyond the double range in an override") {
    const Run r =
        pronk(dir, {"simulate", kSceneDir + "case1_body_only.json", "--set", "/body/mass=1e400"});
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK_THAT(r.err, Contains("/body/mass: expected a finite number"));
  }
  SECTION("a scene that is not an object") {
    write_file(dir / "list.json", "[1, 2, 3]");
    const Run r = pronk(dir, {"simulate", "list.json"});
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("pronk: error: list.json: /: expected an object, found array"));
  }
}

TEST_CASE("bad --set overrides exit 2 naming the pointer", "[cli][errors]") {
  TempDir dir("cli");
  const std::string scene = kSceneDir + "case1_body_only.json";
  SECTION("a value out of range") {
    const Run r = pronk(dir, {"simulate", scene, "--set", "/body/mass=-1", "--out", dir / "o"});
    check_bad_input(r, scene, "/body/mass", "a finite number in [1e-06, 1000000]");
    CHECK_THAT(r.err, Contains("found number -1"));
    CHECK_FALSE(fs::exists(dir / "o"));
  }
  SECTION("a pointer whose parent is missing") {
    const Run r = pronk(dir, {"simulate", scene, "--set", "/nope/x=1"});
    check_bad_input(r, "command line (--set /nope/x=1)", "/nope/x",
                    "a pointer whose parent exists in the scene");
  }
  SECTION("an assignment without '='") {
    const Run r = pronk(dir, {"simulate", scene, "--set", "/body/mass"});
    CHECK(r.code == 2);
    CHECK(count_lines(r.err) == 1);
    CHECK_THAT(r.err, Contains("expected --set /json/pointer=value"));
  }
  SECTION("an array index past the end") {
    const Run r = pronk(dir, {"simulate", scene, "--set", "/initial/position/5=1"});
    check_bad_input(r, "command line (--set /initial/position/5=1)", "/initial/position/5",
                    "an index below 3");
  }
}

TEST_CASE("a good run writes every output, its resolved scene reruns identically",
          "[cli][outputs]") {
  TempDir dir("cli");
  const std::string scene = kSceneDir + "case1_body_only.json";
  const Run r = pronk(dir, {"simulate", scene, "--set", "/simulation/duration=1", "--out", "run1"});
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("case1_body_only (impulse model): completed"));
  CHECK_THAT(r.out, Contains("outputs in run1/"));
  for (const char* f : {"trajectory.csv", "strides.csv", "summary.json", "scene.resolved.json",
                        "motion.gp", "strides.gp"}) {
    INFO(f);
    CHECK(fs::is_regular_file(dir / ("run1/" + std::string(f))));
  }
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(dir / "run1")) {
    CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
  }

  const json summary = json::parse(slurp(dir / "run1/summary.json"));
  CHECK(summary["status"] == "completed");
  CHECK(summary["model"] == "impulse");
  CHECK(summary["scene"] == "case1_body_only");
  CHECK(summary["reason"] == "reached t = 1 s");
  CHECK(summary["t_end"] == 1.0);
  CHECK(summary["metrics"]["strides"].get<long>() >= 2);
  CHECK(summary["cost"]["touchdowns"] == summary["metrics"]["strides"]);
  CHECK(summary["solver"]["method"] == "dopri5");
  CHECK(summary["solver"]["rtol"] == 1e-9);
  CHECK(summary["metrics"]["max_apex_error_m"].get<double>() < 1e-6);
  check_no_null(summary);

  const json resolved = json::parse(slurp(dir / "run1/scene.resolved.json"));
  CHECK(resolved["simulation"]["duration"] == 1.0);
  CHECK(resolved["body"]["inertia_tensor"][2][2] == 0.0164);
  check_no_null(resolved);

  // 1 s sampled every 5 ms: 201 rows.
  const std::string traj = slurp(dir / "run1/trajectory.csv");
  check_csv(traj, 201);
  CHECK(count_lines(traj) == 202);
  CHECK_THAT(traj, StartsWith("t,x,y,z,"));
  check_csv(slurp(dir / "run1/strides.csv"), 2);

  // The resolved scene fed back reproduces the run byte for byte.
  const Run again = pronk(dir, {"simulate", "run1/scene.resolved.json", "--out", "run2", "-q"});
  REQUIRE(again.code == 0);
  CHECK(again.out.empty());  // -q
  for (const char* f : {"trajectory.csv", "strides.csv", "scene.resolved.json"}) {
    INFO(f);
    CHECK(slurp(dir / ("run2/" + std::string(f))) == slurp(dir / ("run1/" + std::string(f))));
  }
  // The same command again (over the existing outputs) is also identical.
  const Run same =
      pronk(dir, {"simulate", scene, "--set", "/simulation/duration=1", "--out", "run1", "-q"});
  REQUIRE(same.code == 0);
  CHECK(slurp(dir / "run1/trajectory.csv") == slurp(dir / "run2/trajectory.csv"));
  CHECK(slurp(dir / "run1/strides.csv") == slurp(dir / "run2/strides.csv"));
}

TEST_CASE("simulate --model pulse overrides the scene's model", "[cli][outputs]") {
  TempDir dir("cli");
  const Run r = pronk(dir, {"simulate", kSceneDir + "case2_legged_impulse.json", "--model", "pulse",
                            "--set", "/simulation/duration=1", "--out", "p", "-q"});
  INFO("stderr: " << r.err);
  REQUIRE(r.code == 0);
  const json summary = json::parse(slurp(dir / "p/summary.json"));
  CHECK(summary["model"] == "pulse");
  CHECK(summary["status"] == "completed");
  CHECK(summary["metrics"]["peak_leg_force_N"].get<double>() > 0.0);
  CHECK(summary["metrics"]["mean_duty_cycle"].get<double>() > 0.0);
  check_no_null(summary);
  CHECK(json::parse(slurp(dir / "p/scene.resolved.json"))["model"] == "pulse");
  CHECK(fs::is_regular_file(dir / "p/leg_force.gp"));
  check_csv(slurp(dir / "p/trajectory.csv"), 201);
  check_csv(slurp(dir / "p/strides.csv"), 2);
}

TEST_CASE("simulate without figures (--no-figures) writes the same data and the scripts, no SVG",
          "[cli][outputs]") {
  TempDir dir("cli");
  const std::string scene = kSceneDir + "case3_legged_pulse.json";
  const Run with =
      pronk(dir, {"simulate", scene, "--set", "/simulation/duration=1", "--out", "a", "-q"});
  const Run without = pronk(dir, {"simulate", scene, "--set", "/simulation/duration=1", "--out",
                                  "b", "-q", "--no-figures"});
  INFO("stderr: " << with.err << without.err);
  REQUIRE(with.code == 0);
  REQUIRE(without.code == 0);
  CHECK(without.err.empty());  // (no "gnuplot not found" either: nothing was asked of it)
  for (const char* fig : {"motion", "leg_force"}) {
    CHECK(slurp(dir / (std::string("a/") + fig + ".gp")) ==
          slurp(dir / (std::string("b/") + fig + ".gp")));
    CHECK_FALSE(fs::exists(dir / (std::string("b/") + fig + ".svg")));
  }
  // The run and its data do not depend on the figures.
  CHECK(slurp(dir / "a/trajectory.csv") == slurp(dir / "b/trajectory.csv"));
  CHECK(slurp(dir / "a/strides.csv") == slurp(dir / "b/strides.csv"));
  // A figure of an earlier run in the same directory is removed, not left stale.
  if (fs::exists(dir / "a/motion.svg")) {
    const Run again = pronk(dir, {"simulate", scene, "--set", "/simulation/duration=1", "--out",
                                  "a", "-q", "--no-figures"});
    REQUIRE(again.code == 0);
    CHECK_FALSE(fs::exists(dir / "a/motion.svg"));
  }
}

TEST_CASE("a run that falls exits 1 with status fell and finite outputs", "[cli][outputs]") {
  TempDir dir("cli");
  const std::string scene = kSceneDir + "case1_body_only.json";
  // case1 has no angular_velocity key: an element override has no parent.
  CHECK(pronk(dir, {"simulate", scene, "--set", "/initial/angular_velocity/0=40"}).code == 2);

  const Run r = pronk(dir, {"simulate", scene, "--set", "/simulation/duration=1", "--set",
                            "/initial/angular_velocity=[40,0,0]", "--out", "fell", "-q"});
  REQUIRE(r.code == 1);
  CHECK_THAT(r.err, !Contains("pronk: error"));
  // -q keeps a completed run silent, not a fall: one line on stderr says what happened.
  CHECK_THAT(r.err, Contains("pronk simulate: ") && Contains(": fell, body tilted past 60 deg"));
  CHECK(r.out.empty());
  const json summary = json::parse(slurp(dir / "fell/summary.json"));
  CHECK(summary["status"] == "fell");
  CHECK_THAT(summary["reason"].get<std::string>(), Contains("tilted past 60 deg"));
  CHECK(summary["t_end"].get<double>() < 0.1);
  // It fell before the first touchdown, rolled over to the 60 degree limit.
  CHECK(summary["metrics"]["strides"] == 0);
  CHECK(summary["metrics"]["final_roll_deg"].get<double>() == Approx(60.0).margin(1e-6));
  check_no_null(summary);
  const std::string traj = slurp(dir / "fell/trajectory.csv");
  const std::string strides = slurp(dir / "fell/strides.csv");
  for (const std::string* text : {&traj, &strides}) {
    std::string lower(*text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    CHECK(lower.find("nan") == std::string::npos);
    CHECK(lower.find("inf") == std::string::npos);
  }
  check_csv(traj, 1);
  check_csv(strides, 0);
}
