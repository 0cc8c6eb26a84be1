// `pronk simulate` with "method": "auto": summary.json says what auto chose and why in one
// line, the resolved mechanism scene reruns the same run, and bad "accuracy" input exits 2
// naming file, pointer, expected and found.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kRoot = std::string(PRONK_SOURCE_DIR);

/// The shipped mechanism scene `name` without its method, step and tolerances (so on "auto",
/// the default), written into `dir`; returns its path.
std::string without_method(const TempDir& dir, const std::string& name) {
  json doc = json::parse(slurp(kRoot + "/studies/mechanisms/" + name + ".json"));
  for (const char* k : {"method", "rtol", "atol", "h_fixed", "energy_tol"}) {
    doc["simulation"].erase(k);
  }
  const std::string path = dir / (name + ".json");
  write_file(path, doc.dump(2));
  return path;
}

}  // namespace

TEST_CASE("auto on a mechanism: the summary's one line, and the resolved scene reruns",
          "[cli][auto]") {
  TempDir dir("auto");
  // No method named: auto, the default.
  Run r = pronk(dir, {"simulate", without_method(dir, "four_leg_drop"), "--out", "a", "--quiet"});
  REQUIRE(r.code == 0);
  const json s = json::parse(slurp(dir / "a/summary.json"));
  CHECK(s["method"] == "verlet");
  const std::string line = s["method_choice"].get<std::string>();
  CHECK_THAT(line, StartsWith("auto: verlet h=0.00047 s, energy_tol 0.0005"));
  CHECK_THAT(line, Contains("non-smooth contact"));
  CHECK(line.find('\n') == std::string::npos);
  CHECK(s["auto"]["rule"] == 6);
  CHECK(s["auto"]["accuracy_met"] == true);
  // The resolved scene holds the choice as numbers and reruns the same run byte for byte.
  const json resolved = json::parse(slurp(dir / "a/scene.resolved.json"));
  CHECK(resolved["simulation"]["method"] == "verlet");
  CHECK(resolved["simulation"]["h_fixed"].get<double>() == Approx(4.7e-4));
  r = pronk(dir, {"simulate", dir / "a/scene.resolved.json", "--out", "b", "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(slurp(dir / "a/nodes.csv") == slurp(dir / "b/nodes.csv"));
  CHECK(slurp(dir / "a/energy.csv") == slurp(dir / "b/energy.csv"));
  // A named method (the shipped scene's rodas4): no choice reported.
  const std::string scene = kRoot + "/studies/mechanisms/four_leg_drop.json";
  r = pronk(dir, {"simulate", scene, "--set", "/simulation/t_end=0.05", "--out", "c", "--quiet"});
  REQUIRE(r.code == 0);
  const json plain = json::parse(slurp(dir / "c/summary.json"));
  CHECK_FALSE(plain.contains("method_choice"));
  CHECK_FALSE(plain.contains("auto"));
}

TEST_CASE("auto on the full model: the summary's one line", "[cli][auto][robot]") {
  TempDir dir("auto");
  const Run r = pronk(dir, {"simulate", kRoot + "/studies/scenes/pr_running.json", "--set",
                            "/simulation/duration=0.5", "--set",
                            R"(/pseudo_rigid/solver={"method": "auto", "accuracy": 2e-3})", "--out",
                            "a", "--quiet"});
  REQUIRE(r.code == 0);
  const json s = json::parse(slurp(dir / "a/summary.json"));
  CHECK(s["solver"]["method"] == "verlet");
  CHECK_THAT(s["method_choice"].get<std::string>(),
             StartsWith("auto: verlet h=0.00012 s, energy_tol 0 (0.7 x its stability limit"));
  CHECK_THAT(s["method_choice"].get<std::string>(), Contains("energy budget 0.002"));
  CHECK(s["auto"]["accuracy"].get<double>() == 2e-3);
  CHECK(s["auto"]["energy_tol"].get<double>() == 0.0);  // restarts: no budget
  // The resolved scene keeps "auto" (as it keeps auto stiffness) with its accuracy.
  const json resolved = json::parse(slurp(dir / "a/scene.resolved.json"));
  CHECK(resolved["pseudo_rigid"]["solver"]["method"] == "auto");
  CHECK(resolved["pseudo_rigid"]["solver"]["accuracy"].get<double>() == 2e-3);
}

TEST_CASE("bad auto input exits 2 naming file and pointer", "[cli][auto]") {
  TempDir dir("auto");
  const std::string mech = without_method(dir, "pendulum");
  Run r = pronk(dir, {"simulate", mech, "--set", "/simulation/accuracy=\"high\""});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("pendulum.json: /simulation/accuracy: expected"));
  CHECK_THAT(r.err, Contains("\"high\""));
  r = pronk(dir, {"simulate", mech, "--set", "/simulation/method=\"auto\"", "--set",
                  "/simulation/acuracy=1e-3"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/simulation/acuracy"));
  r = pronk(dir, {"simulate", mech, "--set", "/simulation/accuracy=0"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/simulation/accuracy"));
  r = pronk(dir, {"simulate", mech, "--set", "/simulation/method=\"Auto\""});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/simulation/method: expected one of"));
  const std::string robot = kRoot + "/studies/scenes/pr_running.json";
  r = pronk(dir, {"simulate", robot, "--set",
                  R"(/pseudo_rigid/solver={"method": "auto", "accuracy": [1e-3]})"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("pr_running.json: /pseudo_rigid/solver/accuracy: expected"));
  r = pronk(dir, {"simulate", robot, "--set",
                  R"(/pseudo_rigid/solver={"method": "auto", "acuracy": 1e-3})"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/pseudo_rigid/solver/acuracy"));
}

// The settings auto chooses are refused under auto, named or the default, so that a tolerance
// is never silently ignored: exit 2 naming file, pointer, expected and found.
TEST_CASE("auto refuses the step and tolerances it chooses", "[cli][auto]") {
  TempDir dir("auto");
  const std::string mech = without_method(dir, "pendulum");
  Run r = pronk(dir, {"simulate", mech, "--set", "/simulation/rtol=1e-8"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("pendulum.json: /simulation/rtol: expected no rtol under "
                             "\"method\": \"auto\" (the default)"));
  CHECK_THAT(r.err, Contains("found number 1e-08"));
  // A shipped scene switched to auto keeps its rodas4 tolerances: refused, not ignored.
  r = pronk(dir, {"simulate", kRoot + "/studies/mechanisms/satellite.json", "--set",
                  "/simulation/method=\"auto\""});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("satellite.json: /simulation/rtol: expected no rtol under "
                             "\"method\": \"auto\", which chooses it"));
  const std::string robot = kRoot + "/studies/scenes/pr_running.json";
  r = pronk(dir, {"simulate", robot, "--set", R"(/pseudo_rigid/solver={"h_fixed": 1e-4})"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("pr_running.json: /pseudo_rigid/solver/h_fixed: expected no "
                             "h_fixed under \"method\": \"auto\" (the default)"));
  r = pronk(dir, {"simulate", robot, "--set",
                  R"(/pseudo_rigid/solver={"method": "auto", "energy_tol": 1e-4})"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/pseudo_rigid/solver/energy_tol: expected no energy_tol"));
}

// Auto checks its run: a 10 m/s drop onto the default contact drifts 4.8e-3 on auto's first
// choice, so it is rerun once tighter; the summary says so and the resolved scene, which
// holds the rerun's setting, reruns it byte for byte.
TEST_CASE("auto reruns a run that missed its budget, and the resolved scene reproduces it",
          "[cli][auto]") {
  TempDir dir("auto");
  const std::string scene = dir / "impact.json";
  write_file(scene, R"({"kind": "mechanism", "name": "impact",
      "bodies": [{"name": "box", "mass": 1.5, "inertia": [0.0074, 0.0106, 0.0164],
                  "com": [0, 0, 0.2], "velocity": [0, 0, -10]}],
      "surfaces": [{"name": "ground", "type": "plane", "point": [0, 0, 0],
                    "direction": [0, 0, 1], "nodes": ["box.0", "box.1", "box.2", "box.3"]}],
      "simulation": {"t_end": 0.1, "output_interval": 0.005}})");
  Run r = pronk(dir, {"simulate", scene, "--out", "a", "--quiet"});
  REQUIRE(r.code == 0);
  const json s = json::parse(slurp(dir / "a/summary.json"));
  CHECK(s["auto"]["reruns"] == 1);
  CHECK(s["auto"]["first_run_drift_relative"].get<double>() > 1e-3);
  CHECK(s["auto"]["accuracy_met"] == true);
  CHECK_THAT(s["method_choice"].get<std::string>(), Contains("; rerun: the first run drifted"));
  r = pronk(dir, {"simulate", dir / "a/scene.resolved.json", "--out", "b", "--quiet"});
  REQUIRE(r.code == 0);
  CHECK(slurp(dir / "a/energy.csv") == slurp(dir / "b/energy.csv"));
  CHECK(slurp(dir / "a/nodes.csv") == slurp(dir / "b/nodes.csv"));
}
