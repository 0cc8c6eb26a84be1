// What `pronk simulate` itself reports at the extremes: the exit code, the
// warnings in summary.json and on stdout, and no NaN in any output file.
#include <sys/wait.h>
#include <unistd.h>

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
