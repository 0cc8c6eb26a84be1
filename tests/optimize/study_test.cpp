// The objective API and studies: determinism across thread counts, failures
// as data, study-file errors, the journal (resume, torn lines) and reproduce.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/journal.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"

using namespace pronk;
using namespace pronk::optimize;
using nlohmann::json;

namespace {

std::string scenes_dir() {
  std::string dir = PRONK_SOURCE_DIR;
  dir.append("/studies/scenes");  // (operator+ here trips GCC 12's false -Wstringop-overflow)
  return dir;
}

// A small study over the legged impulse robot (fast: a few ms per evaluation).
json small_study(const std::string& algorithm = "LN_BOBYQA", long evals = 30) {
  return json::parse(R"({
    "name": "test_study",
    "scene": "case2_legged_impulse.json",
    "parameters": [
      {"name": "kp_roll", "pointer": "/controller/kp/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "kd_roll", "pointer": "/controller/kd/3", "lower": 0.002, "upper": 0.05, "log": true},
      {"name": "bank_kp", "pointer": "/controller/bank/kp", "lower": 0.01, "upper": 0.2}
    ],
    "scenarios": {"duration": 3,
                  "list": [{"name": "nominal"}],
                  "random": {"count": 5, "seed": 9, "tilt_deg": [0, 8], "lateral_offset": [0, 0.3]}},
    "objective": [{"metric": "y_error", "aggregate": "mean"},
                  {"metric": "attitude_error", "aggregate": "cvar", "alpha": 0.5, "weight": 0.5}],
    "constraints": [{"metric": "spectral_radius", "max": 0.95}],
    "optimizer": {"library": "nlopt", "algorithm": ")" +
                     algorithm + R"(", "max_evaluations": )" + std::to_string(evals) + R"(}
  })");
}

std::string temp_dir() {
  std::string t = (std::filesystem::temp_directory_path() / "pronk_study_XXXXXX").string();
  REQUIRE(mkdtemp(t.data()) != nullptr);
  return t;
}

std::string read_file(const std::string& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Study parse(const json& doc) { return parse_study(doc, "test_study.json", scenes_dir()); }

}  // namespace

TEST_CASE("evaluations are identical whatever the thread count", "[optimize][determinism]") {
  const Study st = parse(small_study());
  EvaluatorConfig c1 = st.evaluator, c2 = st.evaluator;
  c1.threads = 1;
  c2.threads = 2;
  const Evaluator e1(c1), e2(c2);
  const std::vector<double> x = {0.3, 0.6, 0.2};
  const Evaluation a = e1.evaluate_full(x), b = e2.evaluate_full(x);
  REQUIRE(a.ok);
  CHECK(a.cost == b.cost);  // bit-identical
  CHECK(a.constraints == b.constraints);
  CHECK(a.aggregated == b.aggregated);
  CHECK(a.scenarios.size() == 6);
  // Later evaluations start their trials longest first, by the durations the last one
  // measured (job_schedule.hpp): the same numbers, every trial in its own slot.
  for (int round = 0; round < 2; ++round) {
    const Evaluation c = e2.evaluate_full(x);
    CHECK(c.cost == a.cost);
    CHECK(c.aggregated == a.aggregated);
    REQUIRE(c.scenarios.size() == a.scenarios.size());
    for (size_t i = 0; i < a.scenarios.size(); ++i) {
      CHECK(c.scenarios[i].name == a.scenarios[i].name);
      CHECK(c.scenarios[i].metrics == a.scenarios[i].metrics);
    }
  }
  // Batch (parallel over points) gives the same numbers as one at a time.
  const auto batch = e2.evaluate_batch({x, {0.1, 0.1, 0.9}});
  CHECK(batch[0].cost == a.cost);
  CHECK(batch[1].cost == e1.evaluate(std::vector<double>{0.1, 0.1, 0.9}).cost);
  // The cost is the weighted sum of its aggregated terms.
  CHECK(a.cost ==
        Approx(a.aggregated.at("mean(y_error)") + 0.5 * a.aggregated.at("cvar(attitude_error)")));
  CHECK(a.constraints[0] == Approx(a.spectral_radius - 0.95));
}

TEST_CASE("failures are data: fallen runs and invalid scenes give finite numbers", "[optimize]") {
  json doc = small_study();
  // The leg length may reach zero or below: an invalid scene for these parameters.
  doc["parameters"].push_back(
      {{"name", "leg_length"}, {"pointer", "/legs/length"}, {"lower", -0.1}, {"upper", 0.3}});
  doc["parameters"].push_back(
      {{"name", "kd_z"}, {"pointer", "/controller/kd/2"}, {"lower", 0.0}, {"upper", 3.0}});
  const Study st = parse(doc);
  const Evaluator ev(st.evaluator);
  const Evaluation bad = ev.evaluate_full({0.5, 0.5, 0.5, 0.0, 0.5});
  CHECK_FALSE(bad.ok);
  CHECK(bad.failure.find("/legs/length") != std::string::npos);
  CHECK(std::isfinite(bad.cost));
  CHECK(bad.cost == st.evaluator.failure_cost);
  for (double g : bad.constraints) CHECK(g > 0);
  // No vertical push (Kd_z = 0): the robot falls; metrics stay finite.
  const Evaluation fell = ev.evaluate_full({0.5, 0.5, 0.5, 0.9, 0.0});
  REQUIRE(fell.ok);
  CHECK(fell.aggregated.at("fell") > 0.0);
  for (const auto& [k, v] : fell.aggregated) CHECK(std::isfinite(v));
  for (const auto& s : fell.scenarios) {
    if (s.status == "fell") {
      CHECK(s.metrics.at("y_error") >= 1.0);  // the fall penalty
      CHECK_FALSE(s.reason.empty());
    }
  }
}

TEST_CASE("bad studies are input errors naming the pointer", "[optimize][input]") {
  auto expect = [](json doc, const std::string& pointer) {
    try {
      parse(doc);
      FAIL("no error for " << pointer);
    } catch (const io::InputError& e) {
      CHECK(e.pointer() == pointer);
      CHECK(e.file() == "test_study.json");
    }
  };
  json d = small_study();
  d["objectiv"] = json::array();
  expect(d, "/objectiv");
  d = small_study();
  d["objective"][0]["metric"] = "speed";
  expect(d, "/objective/0/metric");
  d = small_study();
  d["parameters"][0]["pointer"] = "/legs/kind";
  expect(d, "/parameters/0/pointer");
  d = small_study();
  d["parameters"][1]["upper"] = 0.001;
  expect(d, "/parameters/1/upper");
  d = small_study();
  d["constraints"][0]["min"] = 0.1;
  expect(d, "/constraints/0/max");
  d = small_study();
  d["optimizer"]["library"] = "scipy";
  expect(d, "/optimizer/library");
  d = small_study();
  d["scenarios"]["random"]["tilt_deg"] = {5, 1};
  expect(d, "/scenarios/random/tilt_deg");
}

TEST_CASE("a study's journal is the same with 1 and 2 threads, and --resume replays it",
          "[optimize][determinism][journal]") {
  const Study st = parse(small_study("LN_COBYLA", 25));
  const std::string d1 = temp_dir(), d2 = temp_dir(), d3 = temp_dir();
  StudyRunOptions o;
  o.threads = 1;
  o.out_dir = d1;
  const StudyOutcome r1 = run_study(st, o);
  o.threads = 2;
  o.out_dir = d2;
  const StudyOutcome r2 = run_study(st, o);
  const std::string j1 = read_file(d1 + "/journal.jsonl"), j2 = read_file(d2 + "/journal.jsonl");
  CHECK(fnv1a_hex(j1) == fnv1a_hex(j2));
  CHECK(r1.result.best_x == r2.result.best_x);
  CHECK(r1.result.evaluations == 25);
  CHECK(std::filesystem::exists(d1 + "/design.json"));
  CHECK(std::filesystem::exists(d1 + "/history.csv"));
  CHECK(std::filesystem::exists(d1 + "/summary.md"));

  // An interrupted run: the first 10 records and half of the 11th survived.
  std::istringstream lines(j1);
  std::string line, partial;
  for (int i = 0; i < 11 && std::getline(lines, line);) {
    partial += line + "\n";
    ++i;
  }
  std::getline(lines, line);
  partial += line.substr(0, line.size() / 2);  // torn write, no newline
  {
    std::ofstream out(d3 + "/journal.jsonl");
    out << partial;
  }
  const JournalContents torn = read_journal(d3 + "/journal.jsonl");
  CHECK(torn.torn_tail);
  CHECK(torn.records.size() == 10);
  o.out_dir = d3;
  o.resume = false;
  CHECK_THROWS_AS(run_study(st, o), io::InputError);  // an existing journal needs --resume
  o.resume = true;
  const StudyOutcome r3 = run_study(st, o);
  CHECK(r3.replayed == 10);
  CHECK(read_file(d3 + "/journal.jsonl") == j1);
  CHECK(r3.result.best_x == r1.result.best_x);

  // A journal of another study is refused.
  json other = small_study("LN_COBYLA", 25);
  other["scenarios"]["duration"] = 2;
  CHECK_THROWS_AS(run_study(parse(other), o), io::InputError);

  // pronk reproduce: bit-identical on this build (exit 0); a tampered metric fails (exit 1).
  const std::string cmd =
      std::string(PRONK_EXE) + " reproduce " + d1 + "/design.json > " + d1 + "/rep.txt 2>&1";
  CHECK(std::system(cmd.c_str()) == 0);
  CHECK(read_file(d1 + "/rep.txt").find("reproduced: 0 of") != std::string::npos);
  json design = json::parse(read_file(d1 + "/design.json"));
  design["metrics"]["y_error"] = design["metrics"]["y_error"].get<double>() * 1.01;
  {
    std::ofstream out(d1 + "/tampered.json");
    out << design.dump();
  }
  const std::string cmd2 =
      std::string(PRONK_EXE) + " reproduce " + d1 + "/tampered.json > /dev/null 2>&1";
  CHECK(WEXITSTATUS(std::system(cmd2.c_str())) == 1);
  for (const auto& d : {d1, d2, d3}) std::filesystem::remove_all(d);
}

TEST_CASE("fast parameter binding builds the same scene as the JSON route", "[optimize]") {
  const Study st = parse(small_study());
  const Evaluator ev(st.evaluator);
  for (const std::vector<double>& x : {std::vector<double>{0.0, 0.5, 1.0}, {0.123, 0.77, 0.31}}) {
    const scene::Scene fast = ev.scene_at(x);
    const scene::Scene slow = io::parse_scene(
        bind_parameters(st.evaluator.scene_doc, st.evaluator.parameters, x), "scene");
    CHECK(io::scene_to_json(fast).dump() == io::scene_to_json(slow).dump());
  }
}
