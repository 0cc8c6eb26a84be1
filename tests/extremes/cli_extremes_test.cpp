// What `pronk simulate` itself reports at the extremes: the exit code, the
// warnings in summary.json and on stdout, and no NaN in any output file.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

/// No "nan" or "inf" token in any output file of the run directory.
void check_no_nan(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.ends_with(".csv") || name.ends_with(".json")) {
      INFO(name);
      const std::string text = slurp(e.path().string());
      CHECK(text.find("nan") == std::string::npos);
      CHECK(text.find("inf") == std::string::npos);
    }
  }
}

}  // namespace

TEST_CASE("extreme CLI: a flexing, penetrating mechanism warns in summary.json and on stdout",
          "[extremes][cli]") {
  TempDir dir("extremes");
  const Run r = pronk(
      dir, {"simulate", std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/four_leg_drop.json",
            "--set", "/simulation/t_end=0.3", "--out", dir / "out"});
  CHECK(r.code == 0);  // warnings do not fail the run
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  CHECK(summary["status"] == "completed");
  REQUIRE(summary["warnings"].contains("strain_above_budget"));
  REQUIRE(summary["warnings"].contains("penetration_above_budget"));
  CHECK(summary["monitors"]["max_internal_strain"].get<double>() > 1e-4);
  CHECK(summary["monitors"]["max_penetration_m"].get<double>() > 1e-4);
  CHECK(r.out.find("warning (strain_above_budget): max internal strain") != std::string::npos);
  check_no_nan(dir / "out");
}

TEST_CASE("extreme CLI: an explicit solver past its limit exits 1 as diverged, files finite",
          "[extremes][cli]") {
  TempDir dir("extremes");
  const Run r =
      pronk(dir, {"simulate",
                  std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/explicit_instability.json",
                  "--set", "/simulation/method=euler", "--out", dir / "out"});
  CHECK(r.code == 1);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  CHECK(summary["status"] == "diverged");
  CHECK(summary["reason"].get<std::string>().find("energy blow-up") != std::string::npos);
  check_no_nan(dir / "out");
}

TEST_CASE("extreme CLI: the small-angle formulation past 15 deg warns once", "[extremes][cli]") {
  TempDir dir("extremes");
  const Run r = pronk(
      dir, {"simulate", std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case1_body_only.json",
            "--set", "/attitude=small_angle_euler123", "--set", "/initial/attitude_deg/0=20",
            "--out", dir / "out"});
  CHECK(r.code == 0);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  REQUIRE(summary["warnings"].size() == 1);
  CHECK(summary["warnings"]["small_angle_range_exceeded"].get<long>() >= 1);
  CHECK(r.out.find("warning: small_angle_range_exceeded") != std::string::npos);
  check_no_nan(dir / "out");
}

namespace {

/// `pronk simulate` of the shipped scene `name` with `set`: exit 2, one line on stderr, and
/// no output directory (nothing written before the refusal).
Run refused(const TempDir& dir, const std::string& name, const std::vector<std::string>& set) {
  std::vector<std::string> args = {
      "simulate", std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + name + ".json"};
  for (const auto& s : set) {
    args.push_back("--set");
    args.push_back(s);
  }
  args.push_back("--out");
  args.push_back(dir / "out");
  const Run r = pronk(dir, args);
  CHECK(r.code == 2);
  CHECK(r.err.find("pronk: error: ") == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(dir / "out"));
  return r;
}

}  // namespace

TEST_CASE("extreme CLI: a robot run that would hold too many samples or strides is exit 2",
          "[extremes][cli]") {
  TempDir dir("extremes");
  for (const char* name : {"case3_legged_pulse", "pr_running"}) {
    INFO(name);
    Run r = refused(dir, name, {"/simulation/duration=1e6"});
    CHECK(r.err.find("/simulation/sample_interval: expected at most 1e+07 trajectory samples "
                     "held in memory (duration / sample_interval), found 2e+08 samples (duration "
                     "1e+06 s / sample_interval 0.005 s)") != std::string::npos);
    r = refused(dir, name, {"/simulation/sample_interval=1e-9"});
    CHECK(r.err.find("found 1e+10 samples") != std::string::npos);
    r = refused(dir, name, {"/simulation/max_strides=1000000000"});
    CHECK(r.err.find("/simulation/max_strides: expected at most 1e+07 stride records held in "
                     "memory, found max_strides 1e+09") != std::string::npos);
  }
}

TEST_CASE("extreme CLI: a fixed step that can skip a whole flight is exit 2", "[extremes][cli]") {
  TempDir dir("extremes");
  Run r = refused(dir, "case1_body_only",
                  {"/simulation/solver/method=\"euler\"", "/simulation/solver/h_fixed=10"});
  CHECK(r.err.find("/simulation/solver/h_fixed: expected a fixed step of at most 0.201928 s, half "
                   "the 0.403855 s flight of the lowest hop height 0.2 m") != std::string::npos);
  CHECK(r.err.find("found h_fixed 10 s (euler)") != std::string::npos);
  r = refused(dir, "pr_running", {R"(/pseudo_rigid/solver={"method": "euler", "h_fixed": 10})"});
  CHECK(r.err.find("/pseudo_rigid/solver/h_fixed: expected a fixed step of at most") !=
        std::string::npos);
}

TEST_CASE("extreme CLI: the full model without gravity is exit 2 with no output",
          "[extremes][cli]") {
  // It was exit 1 after "non-finite state at t = 0 s", with incomplete outputs.
  TempDir dir("extremes");
  for (const char* body : {"four_masses", "rigid"}) {
    INFO(body);
    const Run r = refused(dir, "pr_running",
                          {"/gravity=0", std::string("/pseudo_rigid/body=\"") + body + "\""});
    CHECK(r.err.find("gravity 0 m/s^2: the full model needs gravity > 0") != std::string::npos);
  }
  // Negative gravity is out of the scene's range in every model.
  for (const char* name : {"case1_body_only", "pr_running"}) {
    const Run r = refused(dir, name, {"/gravity=-9.81"});
    CHECK(r.err.find("/gravity: expected") != std::string::npos);
  }
}
