// End-to-end tests of `pronk simulate` on the shipped mechanism scenes
// (studies/mechanisms, shortened with --set): exit codes, output files, no
// NaN anywhere, case 8 (RK4 beyond its stability limit) exits 1 as diverged.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kMechDir = std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/";

void check_finite_json(const json& j, const std::string& where = "") {
  INFO("at " << (where.empty() ? "/" : where));
  CHECK_FALSE(j.is_null());
  if (j.is_number_float()) CHECK(std::isfinite(j.get<double>()));
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) check_finite_json(*it, where + "/" + it.key());
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) check_finite_json(j[i], where + "/" + std::to_string(i));
  }
}

/// Header plus rows of equal column count, every cell a finite number; returns the row count.
size_t check_csv(const std::string& text) {
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
      const double x = std::strtod(cell.c_str(), &end);
      REQUIRE(end != cell.c_str());
      REQUIRE(std::isfinite(x));
    }
  }
  return rows;
}

json check_outputs(const TempDir& dir, const std::string& out) {
  for (const char* f : {"nodes.csv", "bodies.csv", "energy.csv", "summary.json",
                        "scene.resolved.json", "energy.gp", "motion.gp"}) {
    INFO(f);
    CHECK(fs::exists(dir / (out + "/" + f)));
  }
  CHECK(check_csv(slurp(dir / (out + "/nodes.csv"))) >= 2);
  check_csv(slurp(dir / (out + "/bodies.csv")));
  check_csv(slurp(dir / (out + "/energy.csv")));
  const json summary = json::parse(slurp(dir / (out + "/summary.json")));
  check_finite_json(summary);
  check_finite_json(json::parse(slurp(dir / (out + "/scene.resolved.json"))));
  return summary;
}

}  // namespace

TEST_CASE("pronk simulate runs every shipped mechanism scene", "[cli][mechanism]") {
  TempDir dir("mech");
  for (const char* name : {"satellite", "pendulum", "spring_leg_drop", "four_leg_drop"}) {
    INFO(name);
    const Run r = pronk(dir, {"simulate", kMechDir + name + ".json", "--set",
                              "/simulation/t_end=0.3", "--out", name, "--quiet"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const json s = check_outputs(dir, name);
    CHECK(s["status"] == "completed");
    CHECK(s["t_reached"].get<double>() == Approx(0.3));
    CHECK(s["cost"]["steps_accepted"].get<long>() > 0);
    CHECK(s["cost"]["rhs_evaluations"].get<long>() > 0);
    CHECK(s["monitors"]["energy_balance_drift_relative"].get<double>() < 1e-5);
    // The resolved scene runs again to the same result.
    const Run again = pronk(dir, {"simulate", dir / (std::string(name) + "/scene.resolved.json"),
                                  "--out", std::string(name) + "_again", "--quiet"});
    REQUIRE(again.code == 0);
    CHECK(slurp(dir / (std::string(name) + "/nodes.csv")) ==
          slurp(dir / (std::string(name) + "_again/nodes.csv")));
  }
}

TEST_CASE("case 8 scene: RK4 with a big step exits 1 as diverged; a small step completes",
          "[cli][mechanism]") {
  TempDir dir("mech");
  const std::string scene = kMechDir + "explicit_instability.json";
  Run r = pronk(dir, {"simulate", scene, "--set", "/simulation/method=\"rk4\"", "--set",
                      "/simulation/h_fixed=5e-3", "--out", "big"});
  REQUIRE(r.code == 1);
  CHECK_THAT(r.out, Contains("diverged"));
  json s = check_outputs(dir, "big");
  CHECK(s["status"] == "diverged");
  CHECK_THAT(s["reason"].get<std::string>(), Contains("energy blow-up"));

  r = pronk(dir, {"simulate", scene, "--set", "/simulation/h_fixed=2e-4", "--set",
                  "/simulation/t_end=0.2", "--out", "small", "--quiet"});
  REQUIRE(r.code == 0);
  s = check_outputs(dir, "small");
  CHECK(s["status"] == "completed");
  CHECK(s["monitors"]["max_internal_strain"].get<double>() < 1e-3);
}

TEST_CASE("mechanism options: check_jacobian and auto stiffness reach the summary",
          "[cli][mechanism]") {
  TempDir dir("mech");
  const Run r = pronk(dir, {"simulate", kMechDir + "spring_leg_drop.json", "--set",
                            "/simulation/t_end=0.2", "--set", "/simulation/check_jacobian=true",
                            "--set", "/simulation/contact_stiffness=\"auto\"", "--set",
                            "/surfaces/0/stiffness=null", "--out", "o", "--quiet"});
  // null is not a number: a per-surface stiffness must be removed, not nulled -> bad input.
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/surfaces/0/stiffness"));
  const Run ok =
      pronk(dir, {"simulate", kMechDir + "satellite.json", "--set", "/simulation/t_end=0.2",
                  "--set", "/simulation/check_jacobian=true", "--set",
                  "/simulation/internal_stiffness=\"auto\"", "--out", "o", "--quiet"});
  REQUIRE(ok.code == 0);
  const json s = check_outputs(dir, "o");
  CHECK(s["monitors"]["jacobian_check_error"].get<double>() < 1e-6);
  CHECK(s["stiffness"]["internal_auto"] == true);
  CHECK(s["stiffness"]["internal_max_N_per_m"].get<double>() > 0.0);
  // The realised strain stays within the default budget (1e-4).
  CHECK(s["monitors"]["max_internal_strain"].get<double>() < 1e-4);
}

TEST_CASE("bad mechanism input exits 2 naming file and pointer", "[cli][mechanism]") {
  TempDir dir("mech");
  const std::string scene = kMechDir + "pendulum.json";
  Run r = pronk(dir, {"simulate", scene, "--set", "/simulation/method=\"rk9\""});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("pendulum.json: /simulation/method: expected one of"));
  r = pronk(dir, {"simulate", scene, "--set", "/connections/0/stifness=1"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/connections/0/stifness"));
  r = pronk(dir, {"simulate", scene, "--model", "pulse"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/model"));
}
