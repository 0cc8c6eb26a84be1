// Reproducing a design: what design.json records for it (per-trial decisions, the
// perturbation run's tolerances), how reproduce compares on the recording build, on another
// build, with --rtol and --strict, designs recorded before the records, and the design read
// as strictly as any input (every mistyped or inconsistent value an io::InputError naming
// its pointer).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "optimize/design_reader.hpp"
#include "optimize/reproduce.hpp"
#include "optimize/reproduction_record.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"

using namespace pronk;
using namespace pronk::optimize;
using nlohmann::json;

namespace {

const std::string kScenes = std::string(PRONK_SOURCE_DIR) + "/studies/scenes";

// The legged impulse robot over 6 scenarios and 4 held-out trials (milliseconds each).
json rp_study() {
  return json::parse(R"({
    "name": "reproduce_test",
    "scene": "case2_legged_impulse.json",
    "parameters": [
      {"name": "kp_roll", "pointer": "/controller/kp/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "kd_roll", "pointer": "/controller/kd/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "bank_kp", "pointer": "/controller/bank/kp", "lower": 0.01, "upper": 0.2}
    ],
    "scenarios": {"duration": 3, "list": [{"name": "nominal"}],
                  "random": {"count": 5, "seed": 9, "tilt_deg": [0, 8], "lateral_offset": [0, 0.3]}},
    "validation": {"duration": 3, "random": {"count": 4, "seed": 77, "tilt_deg": [0, 8]}},
    "objective": [{"metric": "y_error", "aggregate": "mean"},
                  {"metric": "attitude_error", "aggregate": "cvar", "alpha": 0.5, "weight": 0.5}],
    "constraints": [{"metric": "spectral_radius", "max": 0.95}],
    "optimizer": {"library": "nlopt", "algorithm": "LN_COBYLA", "max_evaluations": 8, "seed": 4}
  })");
}

std::string rp_temp_dir() {
  std::string t = (std::filesystem::temp_directory_path() / "pronk_reproduce_XXXXXX").string();
  REQUIRE(mkdtemp(t.data()) != nullptr);
  return t;
}

json rp_slurp_json(const std::string& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return json::parse(s.str());
}

// The design.json of rp_study(), run once per test case in a temporary directory.
struct Recorded {
  Study study = parse_study(rp_study(), "reproduce_test.json", kScenes);
  std::string dir = rp_temp_dir();
  json design;
  Recorded() {
    StudyRunOptions opt;
    opt.threads = 2;
    opt.out_dir = dir;
    run_study(study, opt);
    design = rp_slurp_json(dir + "/design.json");
  }
  ~Recorded() { std::filesystem::remove_all(dir); }
  std::string path() const { return dir + "/design.json"; }
};

ReproduceOptions rp_options() {
  ReproduceOptions o;
  o.threads = 2;
  return o;
}

const ReproducedValue& value_named(const ReproduceReport& rep, const std::string& name) {
  for (const auto& v : rep.values)
    if (v.name == name) return v;
  FAIL("no value " << name);
  return rep.values.front();
}

}  // namespace

TEST_CASE("a design records its trials' decisions and tolerances from a perturbation run",
          "[optimize][reproduce]") {
  const Recorded r;
  const json& d = r.design;
  // Every scenario's and validation trial's decisions, named as the study names them.
  REQUIRE(d.at("trials").size() == 6);
  CHECK(d.at("trials")[0].at("name") == "nominal");
  REQUIRE(d.at("validation").at("trials").size() == 4);
  long stabilized = 0;
  for (const auto& t : d.at("trials")) stabilized += t.at("stabilized").get<bool>() ? 1 : 0;
  CHECK(d.at("metrics").at("stabilized").get<double>() == static_cast<double>(stabilized) / 6.0);
  CHECK(d.at("build_flags") == pronk::build_flags());

  // The perturbation moves every coordinate by 1e-12, inwards at a bound.
  const std::vector<double> edge = {0.0, 1.0, 0.5};
  for (int k = 0; k < kPerturbations; ++k) {
    const std::vector<double> p = perturbed_unit(edge, k);
    CHECK(p[0] == Approx(1e-12).margin(1e-20));
    CHECK(p[1] == Approx(1.0 - 1e-12).margin(1e-15));
    CHECK(std::abs(std::abs(p[2] - 0.5) - 1e-12) < 1e-16);
  }
  // The recorded tolerances are 4x the largest change of 8 such re-evaluations, computed
  // here again through an evaluator of the study built by hand.
  const json& rec = d.at("reproduction");
  CHECK(rec.at("method") == "perturbation");
  CHECK(rec.at("perturbations") == 8);
  CHECK(rec.at("safety_factor") == 4.0);
  const std::vector<double> unit = d.at("unit").get<std::vector<double>>();
  const Evaluator ev(r.study.evaluator);
  const Evaluation ref = ev.evaluate_full(unit);
  double cost = 0, y = 0;
  for (int k = 0; k < 8; ++k) {
    const Evaluation e = ev.evaluate_full(perturbed_unit(unit, k));
    cost = std::max(cost, std::abs(e.cost - ref.cost));
    y = std::max(y, std::abs(e.aggregated.at("y_error") - ref.aggregated.at("y_error")));
  }
  CHECK(rec.at("tolerance").at("cost").get<double>() == 4 * cost);
  CHECK(rec.at("tolerance").at("metrics").at("y_error").get<double>() == 4 * y);
  // The impulse model over 3 s is not chaotic: the tolerance stays near the perturbation.
  CHECK(y > 0);
  CHECK(y < 1e-8 * ref.aggregated.at("y_error"));
  CHECK(rec.at("validation").at("tolerance").at("metrics").size() == d.at("metrics").size());
}

TEST_CASE("reproduce: bit-identical on the recording build, the design's tolerances on another",
          "[optimize][reproduce]") {
  const Recorded r;
  const ReproduceReport same = reproduce_design(r.design, r.path(), rp_options());
  CHECK(same.same_build);
  CHECK(same.mode == CompareMode::kBitIdentical);
  CHECK(same.reproduced());
  CHECK(same.bit_identical == static_cast<long>(same.values.size()));
  CHECK(same.trials_compared == 10);

  json other = r.design;
  other["commit"] = "0000000";  // recorded by another build
  ReproduceReport rep = reproduce_design(other, r.path(), rp_options());
  CHECK_FALSE(rep.same_build);
  CHECK(rep.mode == CompareMode::kTolerance);
  CHECK(rep.reproduced());
  // A value off by half its tolerance still reproduces; by twice, it does not.
  const double tol = other["reproduction"]["tolerance"]["metrics"]["y_error"].get<double>();
  REQUIRE(tol > 0);
  const double y = other["metrics"]["y_error"].get<double>();
  other["metrics"]["y_error"] = y + 0.5 * tol;
  CHECK(reproduce_design(other, r.path(), rp_options()).reproduced());
  other["metrics"]["y_error"] = y + 2 * tol;
  rep = reproduce_design(other, r.path(), rp_options());
  CHECK_FALSE(rep.reproduced());
  CHECK(rep.mismatches == 1);
  CHECK_FALSE(value_named(rep, "y_error").ok);
  CHECK(value_named(rep, "y_error").tolerance == tol);
  CHECK(rep.decision_differences.empty());
  // --rtol forces the plain relative comparison.
  ReproduceOptions rtol = rp_options();
  rtol.rtol = 1e-3;
  rep = reproduce_design(other, r.path(), rtol);
  CHECK(rep.mode == CompareMode::kRelative);
  CHECK(rep.reproduced());
  // --strict on the recording compiler and flags demands the bits whatever the commit.
  ReproduceOptions strict = rp_options();
  strict.strict = true;
  other["metrics"]["y_error"] = y + 0.5 * tol;
  rep = reproduce_design(other, r.path(), strict);
  CHECK(rep.mode == CompareMode::kBitIdentical);
  CHECK_FALSE(rep.same_build);
  CHECK(rep.mismatches == 1);
}

TEST_CASE("reproduce names every trial whose decisions differ", "[optimize][reproduce]") {
  const Recorded r;
  json d = r.design;
  d["commit"] = "0000000";
  // Trial 2 recorded with the other verdict (and the recorded fraction to match).
  json& t = d["validation"]["trials"][2];
  t["stabilized"] = !t["stabilized"].get<bool>();
  long n = 0;
  for (const auto& x : d["validation"]["trials"]) n += x["stabilized"].get<bool>() ? 1 : 0;
  d["validation"]["metrics"]["stabilized"] = static_cast<double>(n) / 4.0;
  const ReproduceReport rep = reproduce_design(d, r.path(), rp_options());
  CHECK_FALSE(rep.reproduced());
  REQUIRE(rep.decision_differences.size() == 1);
  const DecisionDifference& diff = rep.decision_differences.front();
  CHECK(diff.set == "validation");
  CHECK(diff.index == 2);
  CHECK(diff.recorded.stabilized != diff.reproduced.stabilized);
  CHECK(diff.recorded.name == d["validation"]["trials"][2]["name"]);
  CHECK_FALSE(diff.fragile);
  CHECK(rep.decision_mismatches == 1);
  // Had the perturbation run flipped that trial too (fragile), with the stabilized fraction's
  // tolerance to match, the difference is reported but not required.
  d["reproduction"]["validation"]["fragile_trials"] = json::array({2});
  d["reproduction"]["validation"]["tolerance"]["metrics"]["stabilized"] = 0.5;
  const ReproduceReport fragile = reproduce_design(d, r.path(), rp_options());
  REQUIRE(fragile.decision_differences.size() == 1);
  CHECK(fragile.decision_differences.front().fragile);
  CHECK(fragile.decision_mismatches == 0);
  CHECK(fragile.reproduced());
  // --scenarios-only does not see it.
  ReproduceOptions o = rp_options();
  o.scenarios_only = true;
  const ReproduceReport scen = reproduce_design(d, r.path(), o);
  CHECK(scen.validation_skipped);
  CHECK(scen.reproduced());
  CHECK(scen.trials_compared == 6);
}

TEST_CASE("a design recorded before the per-trial records reproduces the old way",
          "[optimize][reproduce]") {
  const Recorded r;
  json d = r.design;
  for (const char* k : {"trials", "reproduction", "build_flags", "study_document_hash"}) d.erase(k);
  d["validation"].erase("trials");
  // Older still: no model or stability record, and a scene written before the format gained
  // a setting.
  d.erase("model");
  d.erase("stability");
  d["scene"].erase(d["scene"].begin().key());
  const ReproduceReport rep = reproduce_design(d, r.path(), rp_options());
  CHECK_FALSE(rep.decisions_recorded);
  CHECK(rep.mode == CompareMode::kRelative);
  CHECK(rep.rtol == kLegacyRtol);
  CHECK(rep.trials_compared == 0);
  CHECK(rep.reproduced());
}

TEST_CASE("reproduce refuses a relative tolerance that is not a finite number > 0",
          "[optimize][reproduce][input]") {
  const Recorded r;
  for (double bad : {std::nan(""), -1.0, 0.0, HUGE_VAL}) {
    ReproduceOptions o = rp_options();
    o.rtol = bad;
    try {
      reproduce_design(r.design, r.path(), o);
      FAIL("accepted rtol " << bad);
    } catch (const io::InputError& e) {
      CHECK(e.file() == "--rtol");
      CHECK(e.expected() == "a finite relative tolerance > 0");
    }
  }
}

TEST_CASE("design.json is read strictly: every mistyped or inconsistent value is named",
          "[optimize][reproduce][input]") {
  const Recorded r;
  struct Case {
    std::string target;  ///< JSON Pointer of the value to change
    json value;          ///< its new value (null with erase: removed)
    bool erase;
    std::string pointer;   ///< the error's pointer
    std::string expected;  ///< a part of what the error says was expected
  };
  const double kp = r.design["parameters"]["kp_roll"].get<double>();
  const double cost = r.design["cost"].get<double>();
  const std::vector<Case> cases = {
      {"/metrics/y_error", "0.1", false, "/metrics/y_error", "number"},
      {"/initial_metrics/y_error", json::array(), false, "/initial_metrics/y_error", "number"},
      {"/metrics/y_eror", 0.1, false, "/metrics/y_eror", "a metric of the study's model"},
      {"/extra", 1, false, "/extra", "a known key"},
      {"/type", "design", false, "/type", "pronk_design"},
      {"/parameters/kp_roll", kp * 1.01, false, "/parameters/kp_roll", "the design's unit gives"},
      {"/parameters/kp_roll", json(), true, "/parameters/kp_roll", "a recorded value"},
      {"/scene/controller/kp/3", kp * 1.01, false, "/scene/controller/kp/3", "unit gives"},
      {"/scene/extra", 1, false, "/scene/extra", "unit gives"},
      {"/unit/0", 1.5, false, "/unit/0", "[0, 1]"},
      {"/unit/3", 0.5, false, "/unit", "3 numbers"},
      {"/study_document_hash", "0123456789abcdef", false, "/study_document_hash", "hash"},
      {"/study_document/scenarios/random/count", 4, false, "/study_document_hash", "hash"},
      {"/study_hash", 7, false, "/study_hash", "a string"},
      {"/study", "other", false, "/study", "reproduce_test"},
      {"/seed", 5, false, "/seed", "4 (the study's optimizer seed)"},
      {"/model", "pulse", false, "/model", "impulse"},
      {"/optimizer/library", "ipopt", false, "/optimizer/library", "nlopt"},
      {"/optimizer/evaluations", -1, false, "/optimizer/evaluations", ""},
      {"/stability/ok", "yes", false, "/stability/ok", "true or false"},
      {"/cost", cost + 1e-3, false, "/cost", "the cost its metrics give"},
      {"/initial_cost", 12.5, false, "/initial_cost", "the cost its metrics give"},
      {"/initial_metrics/y_error", json(), true, "/initial_metrics/y_error", "recorded value"},
      {"/constraints/0", 0.5, false, "/constraints/0", "the recorded metrics give"},
      {"/validation", json(), false, "/validation", "the validation record"},
      {"/validation", json(), true, "/validation", "a recorded value"},
      {"/validation/scenarios", 5, false, "/validation/scenarios", "4"},
      {"/validation/cost", "x", false, "/validation/cost", "number"},
      {"/validation/trials", json(), true, "/validation/trials", "the validation trials"},
      {"/trials/0/status", "ok", false, "/trials/0/status", "completed"},
      {"/trials/1/name", "nominal", false, "/trials/1/name", "the study's scenario"},
      {"/trials/5", json(), true, "/trials", "an array of 6 trials"},
      {"/trials/0/stabilized", 1, false, "/trials/0/stabilized", "true or false"},
      {"/reproduction", json(), true, "/reproduction", "both or neither"},
      {"/reproduction/tolerance/metrics/y_error", -1.0, false,
       "/reproduction/tolerance/metrics/y_error", ">= 0"},
      {"/reproduction/tolerance/metrics/y_error", json(), true,
       "/reproduction/tolerance/metrics/y_error", "a tolerance"},
      {"/reproduction/validation", json(), false, "/reproduction/validation", "an object"},
      {"/reproduction/fragile_trials", json::array({9}), false, "/reproduction/fragile_trials/0",
       ""},
      {"/stages", json::array(), false, "/stages", "only a staged study's design"},
  };
  for (const Case& c : cases) {
    INFO(c.target << " -> " << c.value.dump() << (c.erase ? " (erased)" : ""));
    json d = r.design;
    const json::json_pointer p(c.target);
    if (c.erase) {
      json& parent = d[p.parent_pointer()];
      if (parent.is_array()) {
        parent.erase(std::stoul(p.back()));
      } else {
        parent.erase(p.back());
      }
    } else {
      d[p] = c.value;
    }
    try {
      read_design(d, r.path());
      FAIL("accepted");
    } catch (const io::InputError& e) {
      CHECK(e.file() == r.path());
      CHECK(e.pointer() == c.pointer);
      CHECK(e.expected().find(c.expected) != std::string::npos);
      CHECK_FALSE(e.found().empty());
    }
  }
  // The design as written passes.
  CHECK_NOTHROW(read_design(r.design, r.path()));
}

TEST_CASE("a staged design's stages agree with the design itself",
          "[optimize][reproduce][stages]") {
  const json doc = json::parse(R"({
    "name": "staged_reproduce_test",
    "scene": "case3_legged_pulse.json",
    "parameters": [
      {"name": "kp_roll", "pointer": "/controller/kp/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "T", "pointer": "/pulse/duration", "lower": 0.02, "upper": 0.12}
    ],
    "scenarios": {"duration": 2, "random": {"count": 2, "seed": 4, "tilt_deg": [0, 8]}},
    "objective": [{"metric": "attitude_error"}],
    "stability": false,
    "cross_evaluate": true,
    "optimizer": {"algorithm": "LN_BOBYQA", "max_evaluations": 4},
    "stages": [{"name": "impulse", "model": "impulse", "parameters": ["kp_roll"]},
               {"name": "pulse", "model": "pulse"}]
  })");
  const StagedStudy st = parse_staged_study(doc, "staged.json", kScenes);
  const std::string dir = rp_temp_dir();
  StudyRunOptions opt;
  opt.out_dir = dir;
  opt.threads = 2;
  REQUIRE(run_staged_study(st, opt).ok);
  const std::string path = dir + "/design.json";
  const json design = rp_slurp_json(path);
  CHECK(reproduce_design(design, path, rp_options()).reproduced());
  CHECK(reproduce_design(rp_slurp_json(dir + "/stages/1_impulse/design.json"),
                         dir + "/stages/1_impulse/design.json", rp_options())
            .reproduced());
  const std::vector<std::pair<std::string, json>> edits = {
      {"/stages/1/cost", 1.0},
      {"/stages/1/parameters/T", 0.05},
      {"/stages/0/name", "pulse"},
      {"/stages/0/extra", 1},
      {"/fidelity_gap/first_stage", "pulse"},
      {"/fidelity_gap/final_design/metrics/y_eror", 1.0},
      {"/cross_evaluation/0/evaluated_by/pulse/cost", "1"},
      {"/staged_study", "other"},
  };
  for (const auto& [target, value] : edits) {
    INFO(target);
    json d = design;
    d[json::json_pointer(target)] = value;
    try {
      read_design(d, path);
      FAIL("accepted");
    } catch (const io::InputError& e) {
      CHECK(e.pointer().rfind(target.substr(0, target.find('/', 1)), 0) == 0);
    }
  }
  // The last stage's own design.json is the staged design's record: a stage file that says
  // otherwise is named (CTest reproduces the staged design only, not that file again).
  const std::string last = dir + "/stages/2_pulse/design.json";
  json stage = rp_slurp_json(last);
  REQUIRE(stage.at("cost") == design.at("cost"));
  stage["cost"] = stage.at("cost").get<double>() + 1.0;
  std::ofstream(last) << stage.dump();
  try {
    read_design(design, path);
    FAIL("accepted a last stage that differs");
  } catch (const io::InputError& e) {
    CHECK(e.file() == last);
    CHECK(e.pointer() == "/cost");
  }
  std::filesystem::remove(last);
  CHECK_NOTHROW(read_design(design, path));  // a staged design without its stage files
  std::filesystem::remove_all(dir);
}
