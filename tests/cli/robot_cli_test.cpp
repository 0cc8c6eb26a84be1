// End-to-end tests of `pronk simulate ROBOT.json --model pseudo_rigid`: the same
// per-stride CSV columns at every fidelity, the full model's extra outputs and
// summary sections, settings unused by a model listed, bad input exits 2.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
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

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

const std::string kCase5 =
    std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case5_pr_hop_height.json";

}  // namespace

TEST_CASE("pronk simulate robot: one scene at three fidelities, same stride columns",
          "[robot][cli]") {
  TempDir dir("robot");
  std::vector<std::string> headers;
  for (const char* model : {"impulse", "pulse", "pseudo_rigid"}) {
    const Run r = pronk(dir, {"simulate", kCase5, "--model", model, "--set",
                              "/simulation/duration=1.2", "--out", dir / model, "--quiet"});
    INFO(model << ": " << r.err);
    REQUIRE(r.code == 0);
    headers.push_back(first_line(slurp(dir / model + "/strides.csv")));
    const json summary = json::parse(slurp(dir / model + "/summary.json"));
    CHECK(summary.at("model") == model);
    REQUIRE(summary.contains("unused_by_this_model"));
    const auto unused = summary.at("unused_by_this_model").get<std::vector<std::string>>();
    const bool pr_unused = std::find(unused.begin(), unused.end(), "/pseudo_rigid") != unused.end();
    CHECK(pr_unused == (std::string(model) != "pseudo_rigid"));
  }
  CHECK(headers[0] == headers[1]);
  CHECK(headers[1] == headers[2]);
  const std::string pr = dir / "pseudo_rigid";
  CHECK(fs::exists(pr + "/energy.csv"));
  CHECK(fs::exists(pr + "/feet.csv"));
  CHECK(fs::exists(pr + "/hop_forces.gp"));
  CHECK(fs::exists(pr + "/energy.gp"));
  CHECK(fs::exists(pr + "/path3d.gp"));
  const json s = json::parse(slurp(pr + "/summary.json"));
  const json& p = s.at("pseudo_rigid");
  // Auto's choice (no method named) meets its default budget, 1e-3 of the energy scale.
  CHECK(p.at("energy_balance_drift_relative").get<double>() < 1e-3);
  CHECK(p.at("max_strain").get<double>() >= 0.0);
  CHECK(p.at("max_penetration_m").get<double>() == 0.0);  // force legs: no feet
  // The same robot in the pulse model, run alongside: force legs reproduce it.
  CHECK(p.at("discrepancy_vs_pulse_model").at("strides_compared").get<long>() >= 2);
  CHECK(p.at("discrepancy_vs_pulse_model").at("max_apex_difference_m").get<double>() < 1e-4);
  // Force legs, no contact: auto chose DOPRI5 (rule 8), which counts RHS calls and no
  // Jacobians.
  CHECK_THAT(s.at("method_choice").get<std::string>(), Catch::Matchers::StartsWith("auto: dopri5"));
  CHECK(s.at("cost").at("rhs_evaluations").get<long>() > 0);
  CHECK(s.at("cost").at("jacobian_evaluations").get<long>() == 0);
}

TEST_CASE("pronk simulate robot: bad pseudo_rigid input exits 2 naming the pointer",
          "[robot][cli]") {
  TempDir dir("robot");
  const Run r = pronk(
      dir, {"simulate", kCase5, "--set", "/pseudo_rigid/legs=\"wheels\"", "--out", dir / "x"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("/pseudo_rigid/legs"));
  CHECK_THAT(r.err, Contains("wheels"));
  const Run k = pronk(
      dir, {"simulate", kCase5, "--set", "/pseudo_rigid/hip_rotaton=true", "--out", dir / "y"});
  CHECK(k.code == 2);
  CHECK_THAT(k.err, Contains("/pseudo_rigid/hip_rotaton"));
}
