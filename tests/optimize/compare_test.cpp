// Comparing designs (optimize/compare.hpp) against an independent reference: what
// `pronk reproduce` re-evaluates for each committed design and what its design.json records.
// A design compared on its own study's trials must give exactly reproduce's numbers (both
// are this binary's), and those within the design's recorded tolerance of the recorded ones
// (0 on the recording build: bit-identical). Committed reduced-model designs only: each test
// takes well under a second of CPU.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/compare.hpp"
#include "optimize/compare_output.hpp"
#include "optimize/reproduce.hpp"
#include "optimize/reproduction_record.hpp"

using namespace pronk;
using namespace pronk::optimize;

namespace {

std::string committed(const std::string& dir) {
  return std::string(PRONK_SOURCE_DIR) + "/results/" + dir + "/design.json";
}

// The value reproduce names `name` ("cost", "m", "validation cost", "validation m") in an
// evaluation of compare.
double compared_value(const DesignEvaluation& e, const std::string& name) {
  const bool validation = name.rfind("validation ", 0) == 0;
  const Evaluation& ev = validation ? *e.validation : e.scenarios;
  const std::string key = validation ? name.substr(11) : name;
  if (key == "cost") return ev.cost;
  const auto it = ev.aggregated.find(key);
  return it == ev.aggregated.end() ? NAN : it->second;
}

// Column `k` of `c` against `pronk reproduce` of the same design: every recorded value (cost
// and metrics of the scenarios and the validation set) equal to reproduce's, within the
// design's own tolerance of the recorded one, and every trial's decisions as recorded.
void check_column_reproduces(const Comparison& c, size_t k) {
  const ComparedDesign& d = c.designs.at(k);
  INFO("design " << d.file);
  CHECK(d.own_study);
  ReproduceOptions ro;
  ro.threads = 1;  // compare ran on 2: the numbers may not depend on it
  const ReproduceReport rep = reproduce_design(io::read_json_file(d.file), d.file, ro);
  REQUIRE(rep.values.size() >= 15);  // the cost and every metric of each set
  for (const ReproducedValue& v : rep.values) {
    INFO(v.name);
    const double got = compared_value(d.evaluation, v.name);
    CHECK(got == v.reproduced);
    CHECK(std::abs(got - v.recorded) <= v.tolerance);
    CHECK(v.ok);
  }
  CHECK(rep.reproduced());
  REQUIRE(d.recorded.scenarios.trials.has_value());
  CHECK(trial_decisions(d.evaluation.scenarios) == *d.recorded.scenarios.trials);
  if (d.recorded.validation) {
    REQUIRE(d.evaluation.validation.has_value());
    CHECK(trial_decisions(*d.evaluation.validation) == *d.recorded.validation->trials);
  }
}

CompareOptions two_threads() {
  CompareOptions o;
  o.threads = 2;
  return o;
}

}  // namespace

TEST_CASE("compare: a committed design against itself gives the numbers it records", "[compare]") {
  const std::string f = committed("study2_legged_pulse_duty50");
  const Comparison c = compare_designs({f, f}, two_threads());
  REQUIRE(c.designs.size() == 2);
  CHECK(c.designs[0].label == "study2_legged_pulse_duty50");
  CHECK(c.designs[1].label == "study2_legged_pulse_duty50_2");
  CHECK(c.notes.empty());
  check_column_reproduces(c, 0);
  check_column_reproduces(c, 1);
  // 64 validation trials, every one stabilized, as design.json records (docs/studies.md).
  const auto& v = *c.designs[0].evaluation.validation;
  CHECK(v.scenarios.size() == 64);
  CHECK(v.aggregated.at("stabilized") == 1.0);
  // The files' table: one row per metric, the two columns equal bit for bit.
  const io::ComparisonData data = comparison_data(c);
  for (const io::ComparisonRow& r : io::comparison_rows(data)) {
    REQUIRE(r.values.size() == 2);
    CHECK(r.values[0] == r.values[1]);
  }
}

TEST_CASE("compare: designs of one study family, each column its own recorded numbers",
          "[compare]") {
  // Study 4: study 2's problem (the same trials, objective and constraints) tuned by three
  // optimizers; each design's column must be what its own design.json records.
  const std::vector<std::string> files = {committed("study4_cobyla"), committed("study4_bobyqa"),
                                          committed("study4_ipopt")};
  const Comparison c = compare_designs(files, two_threads());
  REQUIRE(c.designs.size() == 3);
  CHECK(c.reference_file == files[0]);
  for (size_t k = 0; k < 3; ++k) check_column_reproduces(c, k);
  // The designs differ, so do their validation results (docs/studies.md, study 4: 100 %,
  // 100 %, 89.1 % stabilized).
  CHECK(c.designs[0].evaluation.validation->aggregated.at("stabilized") == 1.0);
  CHECK(c.designs[2].evaluation.validation->aggregated.at("stabilized") ==
        Approx(0.891).margin(1e-3));
  // Every design ran the same trials.
  for (const auto& d : c.designs) {
    REQUIRE(d.evaluation.validation->scenarios.size() == 64);
    CHECK(d.evaluation.validation->scenarios[7].name == "random_7");
  }
}

TEST_CASE("compare: --reference picks whose trials judge, and another study's design says so",
          "[compare]") {
  // Study 1 (body-only robot, impulse model, no validation set) judges study 2's design on
  // its own 16 scenarios: study 1's column is what its design.json records, study 2's is not.
  CompareOptions o = two_threads();
  o.reference = 2;
  const Comparison c = compare_designs(
      {committed("study2_legged_pulse_duty50"), committed("study1_body_only_gains")}, o);
  CHECK(c.reference_file == committed("study1_body_only_gains"));
  CHECK_FALSE(c.designs[0].own_study);
  CHECK(c.designs[0].judged.evaluator.scenarios.scenarios.size() == 16);
  CHECK_FALSE(c.designs[0].judged.validation.has_value());
  CHECK_FALSE(c.designs[0].evaluation.validation.has_value());
  check_column_reproduces(c, 1);
  // Study 2's design keeps its own scene and model (pulse), study 1's its own (impulse).
  CHECK(c.designs[0].judged.evaluator.scene_doc.at("model") == "pulse");
  CHECK(c.designs[1].judged.evaluator.scene_doc.at("model") == "impulse");
  REQUIRE(c.notes.size() >= 2);
  CHECK(c.notes[0].find("different models") != std::string::npos);
}

TEST_CASE("compare: options and models a design cannot take are input errors", "[compare]") {
  const std::string f = committed("study2_legged_pulse_duty50");
  const std::string g = committed("study1_body_only_gains");
  auto error_of = [](const std::vector<std::string>& files, const CompareOptions& o) {
    try {
      compare_designs(files, o);
    } catch (const io::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CompareOptions o;
  CHECK(error_of({f}, o) ==
        "command line: /: expected at least two design.json files to compare, found 1");
  o.model = "rigid";
  CHECK(error_of({f, g}, o) ==
        "--model: /: expected impulse, pulse, pseudo_rigid or mujoco, found \"rigid\"");
  o = {};
  o.reference = 3;
  CHECK(error_of({f, g}, o) ==
        "--reference: /: expected a design's position on the command line, 1 to 2, found 3");
  o = {};
  o.play = "validation:64";
  CHECK(error_of({f, g}, o) ==
        "--play: /: expected a trial of the validation set (0 to 63), "
        "found \"validation:64\"");
  o.play = "trial 3";
  CHECK(error_of({f, g}, o) ==
        "--play: /: expected nominal, scenarios:I or validation:I, found \"trial 3\"");
  // Study 1 has no validation set to redraw.
  o = {};
  o.trials = 8;
  o.reference = 2;
  CHECK(error_of({f, g}, o).rfind("--trials: /: expected a reference design whose study has a "
                                  "validation set of random trials, found ",
                                  0) == 0);
  // The impulse model has no pulses: study 2 tunes the pulse duration, which it ignores.
  o = {};
  o.model = "impulse";
  const std::string e = error_of({f, f}, o);
  CHECK(e.rfind(f + "#/study_document (run on the trials of " + f +
                    ", in the impulse model): /parameters/0/pointer: expected a setting the "
                    "impulse model uses (parameter \"pulse_duration\")",
                0) == 0);
  // A missing file names itself.
  o = {};
  CHECK(error_of({f, "/nonexistent/design.json"}, o) ==
        "/nonexistent/design.json: /: expected a readable JSON file, found no such file or "
        "unreadable");
}

TEST_CASE("compare: the labels of design files", "[compare]") {
  CHECK(design_label("results/study4_cobyla/design.json") == "study4_cobyla");
  CHECK(design_label("out/a b,c/design.json") == "a_b_c");
  CHECK(design_label("stages/1_pulse/design.json") == "1_pulse");
}
