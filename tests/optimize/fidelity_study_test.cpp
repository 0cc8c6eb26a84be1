// The objective API at every fidelity: a study runs its scenarios in the scene's
// (or the study's) model through the one simulate() entry point, binds any scene
// number its model uses and refuses the ones it ignores; multi-fidelity studies
// run their stages in order, each from the previous stage's best, and resume.
#include <catch2/catch.hpp>

#include <cmath>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "optimize/evaluator.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"
#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/robot/robot_simulator.hpp"

using namespace pronk;
using namespace pronk::optimize;
using nlohmann::json;

namespace {

std::string fid_scenes_dir() {
  std::string dir = PRONK_SOURCE_DIR;
  dir.append("/studies/scenes");
  return dir;
}

// The spring-legged robot of the seed's drop and hop tests (case 5 with spring legs),
// hopping in place for a short time: a full-model evaluation costs well under a second.
json fid_spring_hop_study(const std::string& pointer = "/pseudo_rigid/leg_stiffness") {
  return json::parse(R"({
    "name": "fidelity_test",
    "scene": "case5_pr_hop_height.json",
    "scene_overrides": ["/pseudo_rigid/legs=\"spring\"", "/pseudo_rigid/leg_stiffness=400",
                        "/pseudo_rigid/contact_damping=20", "/pseudo_rigid/leg_damping=2",
                        "/simulation/duration=1.2"],
    "parameters": [{"name": "p", "pointer": ")" +
                     pointer + R"(", "lower": 300, "upper": 3000, "log": true}],
    "scenarios": {"duration": 1.2, "list": [{"name": "nominal"}, {"name": "tilted", "tilt_deg": [3, 0, 0]}]},
    "objective": [{"metric": "hop_height_error"}],
    "stability": false,
    "optimizer": {"algorithm": "LN_BOBYQA", "max_evaluations": 3}
  })");
}

Study fid_parse(const json& doc) {
  return parse_study(doc, "fidelity_test.json", fid_scenes_dir());
}

std::string fid_expect_error(const json& doc, const std::string& pointer) {
  try {
    if (is_staged_study(doc)) {
      parse_staged_study(doc, "fidelity_test.json", fid_scenes_dir());
    } else {
      fid_parse(doc);
    }
  } catch (const io::InputError& e) {
    CHECK(e.pointer() == pointer);
    return e.what();
  }
  FAIL("no input error for " << pointer);
  return "";
}

std::string fid_temp_dir() {
  std::string t = (std::filesystem::temp_directory_path() / "pronk_fidelity_XXXXXX").string();
  REQUIRE(mkdtemp(t.data()) != nullptr);
  return t;
}

std::string fid_slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("a full-model study runs the full model: leg stiffness moves the cost",
          "[optimize][fidelity]") {
  const Study st = fid_parse(fid_spring_hop_study());
  const Evaluator ev(st.evaluator);
  const Evaluation soft = ev.evaluate_full({0.0}), stiff = ev.evaluate_full({1.0});
  REQUIRE(soft.ok);
  REQUIRE(stiff.ok);
  CHECK(soft.model == scene::ModelKind::kPseudoRigid);
  CHECK(soft.cost != stiff.cost);
  // The full model's own metrics join the common ones.
  for (const char* k : {"energy_drift", "max_strain", "max_penetration", "max_slip",
                        "peak_actuator_force", "actuator_work_per_m", "cost_of_transport"}) {
    CHECK(soft.aggregated.count(k) == 1);
  }
  CHECK(soft.aggregated.at("max_penetration") > 0.0);  // feet sink into the ground springs
  CHECK(soft.aggregated.at("peak_actuator_force") > 0.0);
  // Reference: the robot simulator called directly on the same scene gives the same
  // hop-height error (the evaluator did not run a reduced model).
  scene::Scene s = ev.scene_at({0.0});
  s.simulation.duration = 1.2;
  const robot::RobotRunResult direct = robot::simulate(s, {false});
  const double target = s.legs.length + s.controller.hop_height;
  double sum = 0;
  long n = 0;
  for (const auto& r : direct.run.strides) {
    if (r.has_apex && r.index > 0) {
      sum += (r.apex_height - target) * (r.apex_height - target);
      ++n;
    }
  }
  REQUIRE(n > 0);
  CHECK(soft.scenarios[0].metrics.at("hop_height_error") == Approx(std::sqrt(sum / n)));
  // Energy-balance drift is reported relative to the run's energy scale.
  CHECK(soft.scenarios[0].metrics.at("energy_drift") ==
        Approx(direct.monitors.energy_drift / direct.monitors.energy_scale));
}

TEST_CASE("a study-level model runs every scenario in that model", "[optimize][fidelity]") {
  json doc = fid_spring_hop_study("/pulse/duration");
  doc["parameters"][0] = {
      {"name", "T"}, {"pointer", "/pulse/duration"}, {"lower", 0.02}, {"upper", 0.1}};
  doc["model"] = "pulse";
  const Study st = fid_parse(doc);
  const Evaluator ev(st.evaluator);
  const Evaluation e = ev.evaluate_full({0.5});
  REQUIRE(e.ok);
  CHECK(e.model == scene::ModelKind::kPulse);
  CHECK(e.aggregated.count("max_penetration") == 0);  // no full-model metrics
  // Reference: the pulse model run directly.
  scene::Scene s = ev.scene_at({0.5});
  s.simulation.duration = 1.2;
  const reduced::RunResult r = reduced::simulate(s, {false, true, false});
  CHECK(e.scenarios[0].strides == r.cost.touchdowns);
}

TEST_CASE("parameters bind to numbers the model uses, and nothing else", "[optimize][input]") {
  // Leg stiffness with force legs (no leg is modelled): the model ignores it.
  json d = fid_spring_hop_study();
  d["scene_overrides"][0] = "/pseudo_rigid/legs=\"force\"";
  std::string msg = fid_expect_error(d, "/parameters/0/pointer");
  CHECK(msg.find("ignores") != std::string::npos);
  CHECK(msg.find("\"p\"") != std::string::npos);
  // A reduced-model study tuning a full-model setting.
  d = fid_spring_hop_study();
  d["model"] = "pulse";
  msg = fid_expect_error(d, "/parameters/0/pointer");
  CHECK(msg.find("/pseudo_rigid") != std::string::npos);
  // A pointer that names no field of the scene format.
  d = fid_spring_hop_study("/pseudo_rigid/leg_stifness");
  fid_expect_error(d, "/parameters/0/pointer");
  // The scene's value (here its default, a damping ratio 0.2 on k = 400 N/m: 0.2 * 2 sqrt(k m / n)
  // for 1.5 kg on 4 legs) outside the bounds: no silent clamp.
  d = fid_spring_hop_study("/pseudo_rigid/leg_damping");
  d["scene_overrides"].erase(3);
  fid_expect_error(d, "/parameters/0/initial");
  // ... and a default inside the bounds is the start.
  d["parameters"][0]["lower"] = 0.0;
  d["parameters"][0]["upper"] = 20.0;
  d["parameters"][0]["log"] = false;
  const Study st = fid_parse(d);
  CHECK(st.evaluator.parameters[0].initial ==
        Approx(0.4 * std::sqrt(400 * 1.5 / 4)).epsilon(1e-14));
  // A full-model metric in a reduced-model study.
  d = fid_spring_hop_study("/pulse/duration");
  d["parameters"][0] = {
      {"name", "T"}, {"pointer", "/pulse/duration"}, {"lower", 0.02}, {"upper", 0.1}};
  d["model"] = "impulse";
  d["parameters"][0]["pointer"] = "/controller/hop_height";
  d["parameters"][0]["upper"] = 0.3;
  d["objective"][0]["metric"] = "max_strain";
  fid_expect_error(d, "/objective/0/metric");
  // Stability on passive legs: the stride map cannot be fitted.
  d = fid_spring_hop_study();
  d["stability"] = true;
  d["scene_overrides"].push_back("/pseudo_rigid/actuators=false");
  fid_expect_error(d, "/stability");
}

namespace {

// Impulse then pulse: two cheap stages over the legged robot.
json fid_staged_study() {
  return json::parse(R"({
    "name": "staged_test",
    "scene": "case3_legged_pulse.json",
    "parameters": [
      {"name": "kp_roll", "pointer": "/controller/kp/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "bank_kp", "pointer": "/controller/bank/kp", "lower": 0.01, "upper": 0.2},
      {"name": "T", "pointer": "/pulse/duration", "lower": 0.02, "upper": 0.12}
    ],
    "scenarios": {"duration": 3, "random": {"count": 3, "seed": 4, "tilt_deg": [0, 8]}},
    "objective": [{"metric": "attitude_error"}, {"metric": "y_error"}],
    "stability": false,
    "optimizer": {"algorithm": "LN_BOBYQA", "max_evaluations": 12},
    "stages": [
      {"name": "impulse", "model": "impulse", "parameters": ["kp_roll", "bank_kp"]},
      {"name": "pulse", "model": "pulse", "optimizer": {"algorithm": "LN_COBYLA", "max_evaluations": 10}}
    ]
  })");
}

}  // namespace

TEST_CASE("staged studies: bad stages are input errors", "[optimize][input][stages]") {
  json d = fid_staged_study();
  d["stages"][1].erase("model");
  fid_expect_error(d, "/stages/1/model");
  d = fid_staged_study();
  d["stages"][1]["start"] = "nothing";
  fid_expect_error(d, "/stages/1/start");
  d = fid_staged_study();
  d["stages"][0]["budget"] = 3;
  fid_expect_error(d, "/stages/0/budget");
  d = fid_staged_study();
  d["stages"][0]["parameters"] = {"kp_roll", "T"};  // the impulse model has no pulse
  const std::string msg = fid_expect_error(d, "/parameters/1/pointer");
  CHECK(msg.find("stage \"impulse\"") != std::string::npos);
  d = fid_staged_study();
  d["stages"][1]["parameters"] = {"kp_roll"};  // T is tuned by no stage
  fid_expect_error(d, "/parameters/2");
}

TEST_CASE("staged studies run in order, report the fidelity gap and resume byte for byte",
          "[optimize][stages]") {
  json doc = fid_staged_study();
  doc["cross_evaluate"] = true;
  const StagedStudy st = parse_staged_study(doc, "staged_test.json", fid_scenes_dir());
  const std::string dir = fid_temp_dir();
  StudyRunOptions opt;
  opt.out_dir = dir;
  opt.threads = 2;
  const StagedOutcome o = run_staged_study(st, opt);
  REQUIRE(o.ok);
  REQUIRE(o.stages.size() == 2);
  // The second stage started from the first stage's tuned values.
  const json d2 = json::parse(fid_slurp(dir + "/stages/2_pulse/design.json"));
  const json d1 = json::parse(fid_slurp(dir + "/stages/1_impulse/design.json"));
  const json start2 = d2.at("study_document").at("parameters");
  CHECK(start2[0].at("initial") == d1.at("parameters").at("kp_roll"));
  CHECK(start2[1].at("initial") == d1.at("parameters").at("bank_kp"));
  // The fidelity gap: the first stage's design in the pulse model, checked against an
  // evaluator built by hand from the pulse stage's study.
  const Study pulse_at_first = stage_study(st, 1, o.stages[0].values);
  const Evaluator ev(pulse_at_first.evaluator);
  CHECK(o.gap_first.cost == ev.evaluate_full(ev.initial_point()).cost);
  const json design = json::parse(fid_slurp(dir + "/design.json"));
  CHECK(design.at("stages").size() == 2);
  CHECK(design.at("fidelity_gap").at("first_stage_design").at("cost") == o.gap_first.cost);
  CHECK(design.at("cost") == d2.at("cost"));
  // Every design in every stage: the diagonal is each stage's own tuned cost, the
  // off-diagonal corner is the fidelity gap.
  REQUIRE(o.cross.size() == 2);
  CHECK(o.cross[0][1].cost == o.gap_first.cost);
  CHECK(o.cross[1][1].cost == o.final_best.cost);
  CHECK(o.cross[0][0].cost == Approx(d1.at("cost").get<double>()).epsilon(1e-9));
  CHECK(o.cross[1][1].cost == Approx(d2.at("cost").get<double>()).epsilon(1e-9));
  CHECK(design.at("cross_evaluation").size() == 2);
  // Resume after a crash in the second stage: its journal cut to 5 lines and the
  // final files gone. The journal comes back byte for byte.
  const std::string j2 = dir + "/stages/2_pulse/journal.jsonl";
  const std::string full = fid_slurp(j2);
  std::string cut;
  std::istringstream in(full);
  std::string line;
  for (int i = 0; i < 5 && std::getline(in, line); ++i) cut += line + "\n";
  std::ofstream(j2, std::ios::binary) << cut;
  std::filesystem::remove(dir + "/stages/2_pulse/design.json");
  std::filesystem::remove(dir + "/design.json");
  const std::string j1 = fid_slurp(dir + "/stages/1_impulse/journal.jsonl");
  opt.resume = true;
  const StagedOutcome again = run_staged_study(st, opt);
  CHECK(again.stages[0].skipped);
  CHECK_FALSE(again.stages[1].skipped);
  CHECK(fid_slurp(j2) == full);
  CHECK(fid_slurp(dir + "/stages/1_impulse/journal.jsonl") == j1);
  CHECK(again.final_best.cost == o.final_best.cost);
  std::filesystem::remove_all(dir);
}
