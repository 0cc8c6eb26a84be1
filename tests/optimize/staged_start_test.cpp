// Full-model stages that start from reduced designs: the leg stiffness, which the reduced
// models do not have, starts where the reduced design's stance time puts it (its stance
// half-period pi sqrt(m / (n k)) = the pulse duration), unless the study fixes it.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "optimize/staged_study.hpp"
#include "io/load/scene_loader.hpp"

using namespace pronk;
using namespace pronk::optimize;
using nlohmann::json;

namespace {

std::string ss_scenes_dir() { return std::string(PRONK_SOURCE_DIR) + "/studies/scenes"; }

// Case 5's robot (1.5 kg, four legs) on spring legs, its full-model settings left to the
// defaults (no leg stiffness), hopping in place: pulse stage (pulse duration), then the full
// model (leg stiffness and damping).
json ss_study() {
  return json::parse(R"({
    "name": "staged_start",
    "scene": "case5_pr_hop_height.json",
    "scene_overrides": ["/pseudo_rigid={\"foot_mass\": 0.001}", "/simulation/duration=0.8"],
    "parameters": [
      {"name": "T", "pointer": "/pulse/duration", "lower": 0.03, "upper": 0.09, "initial": 0.04},
      {"name": "k", "pointer": "/pseudo_rigid/leg_stiffness", "lower": 300, "upper": 6000, "log": true},
      {"name": "c", "pointer": "/pseudo_rigid/leg_damping", "lower": 0, "upper": 5, "initial": 0}
    ],
    "scenarios": {"duration": 0.8, "list": [{"name": "tilted", "tilt_deg": [4, 0, 0]}]},
    "objective": [{"metric": "hop_height_error"}],
    "stability": false,
    "optimizer": {"algorithm": "LN_BOBYQA", "max_evaluations": 4},
    "stages": [
      {"name": "pulse", "model": "pulse", "parameters": ["T"]},
      {"name": "full", "model": "pseudo_rigid", "parameters": ["k", "c"],
       "optimizer": {"algorithm": "LN_BOBYQA", "max_evaluations": 2}}
    ]
  })");
}

std::string ss_temp_dir() {
  std::string tmpl = "/tmp/pronk_staged_start_XXXXXX";
  REQUIRE(::mkdtemp(tmpl.data()) != nullptr);
  return tmpl;
}

json ss_read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream b;
  b << in.rdbuf();
  return json::parse(b.str());
}

// m (pi / T)^2 / n for case 5's 1.5 kg on four legs [N/m].
double stiffness_for(double stance) { return 1.5 * M_PI * M_PI / (4.0 * stance * stance); }

}  // namespace

TEST_CASE("a full-model stage starts the leg stiffness at the pulse design's stance time",
          "[optimize][stages]") {
  const StagedStudy st = parse_staged_study(ss_study(), "staged_start.json", ss_scenes_dir());
  CHECK(st.leg_stiffness_follows);
  CHECK(st.leg_stiffness_parameter == "k");
  const std::string dir = ss_temp_dir();
  StudyRunOptions opt;
  opt.out_dir = dir;
  opt.threads = 2;
  const StagedOutcome o = run_staged_study(st, opt);
  REQUIRE(o.stages.size() == 2);
  const double tuned_T = o.stages[0].values.at("T");
  const json full = ss_read(dir + "/stages/2_full/design.json");
  const json start = full.at("study_document").at("parameters");
  REQUIRE(start[0].at("name") == "k");
  CHECK(start[0].at("initial").get<double>() == Approx(stiffness_for(tuned_T)).epsilon(1e-12));
  // Not the nominal scene's stiffness (the 50 ms pulse the scene itself sets).
  CHECK(std::abs(start[0].at("initial").get<double>() - stiffness_for(0.05)) > 10.0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a leg stiffness the study fixes, or no stage tunes, is not restarted",
          "[optimize][stages]") {
  // Fixed by the scene.
  json fixed = ss_study();
  fixed["scene_overrides"][0] = "/pseudo_rigid={\"foot_mass\": 0.001, \"leg_stiffness\": 700}";
  CHECK_FALSE(
      parse_staged_study(fixed, "staged_start.json", ss_scenes_dir()).leg_stiffness_follows);
  // Fixed by the parameter's "initial".
  json initial = ss_study();
  initial["parameters"][1]["initial"] = 900;
  CHECK_FALSE(
      parse_staged_study(initial, "staged_start.json", ss_scenes_dir()).leg_stiffness_follows);
  // No stage tunes it: every full-model stage runs the stiffness of the design's pulse.
  json untuned = ss_study();
  untuned["parameters"].erase(1);
  untuned["stages"][1]["parameters"] = {"c"};
  const StagedStudy st = parse_staged_study(untuned, "staged_start.json", ss_scenes_dir());
  REQUIRE(st.leg_stiffness_follows);
  REQUIRE(st.leg_stiffness_parameter.empty());
  const Study full = stage_study(st, 1, {{"T", 0.07}, {"c", 1.0}});
  CHECK(full.evaluator.scene_doc.at("pseudo_rigid").at("leg_stiffness").get<double>() ==
        Approx(stiffness_for(0.07)).epsilon(1e-12));
  const Study pulse = stage_study(st, 0, {{"T", 0.07}, {"c", 1.0}});
  CHECK(pulse.evaluator.scene_doc.at("pseudo_rigid").at("leg_stiffness").get<double>() ==
        Approx(stiffness_for(0.05)).epsilon(1e-12));  // the nominal scene's
}
