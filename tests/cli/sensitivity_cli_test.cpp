// End-to-end `pronk sensitivity` on a committed reduced-model design (study 1, impulse model):
// it runs, writes its files, its elasticities are finite, one derivative agrees with an
// independent central difference of the design's own evaluator, the numbers do not depend on
// the thread count, and bad input exits 2 naming the option or the JSON Pointer.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/load/scene_loader.hpp"
#include "optimize/design_reader.hpp"
#include "optimize/evaluator.hpp"
#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kDesign =
    std::string(PRONK_SOURCE_DIR) + "/results/study1_body_only_gains/design.json";

// The row of sensitivity.json's local derivatives for (output, input).
const json& derivative_row(const json& s, const std::string& output, const std::string& input) {
  for (const json& r : s.at("local").at("derivatives")) {
    if (r.at("output") == output && r.at("input") == input) return r;
  }
  FAIL("no derivative of " << output << " by " << input);
  static const json none;
  return none;
}

// The cost of the design's own evaluator with parameter `j` at value `x` (others at the design).
double cost_with(const pronk::optimize::RecordedDesign& d, size_t j, double x) {
  pronk::optimize::EvaluatorConfig cfg = d.study.evaluator;
  cfg.threads = 2;
  const pronk::optimize::Evaluator ev(cfg);
  std::vector<double> unit = d.unit;
  unit[j] = cfg.parameters[j].to_unit(x);
  return ev.evaluate_full(unit).cost;
}

// The cost with the robot's mass scaled by 1 + `f`: in the scene (robot and controller alike,
// `plant` false), or as a plant draw on every scenario (the controller keeps the design's mass).
double cost_with_mass(const pronk::optimize::RecordedDesign& d, double f, bool plant) {
  pronk::optimize::EvaluatorConfig cfg = d.study.evaluator;
  cfg.threads = 2;
  if (plant) {
    for (auto& sc : cfg.scenarios.scenarios) sc.plant.push_back({"/body/mass", true, f});
  } else {
    cfg.scene_doc["body"]["mass"] = cfg.scene_doc["body"]["mass"].get<double>() * (1.0 + f);
  }
  return pronk::optimize::Evaluator(cfg).evaluate_full(d.unit).cost;
}

// Checks sensitivity.json's d cost / d mass against an independent central difference.
void check_mass_derivative(const json& s, const pronk::optimize::RecordedDesign& d, bool plant) {
  const double m = d.study.evaluator.scene_doc["body"]["mass"].get<double>();
  const double dm = (cost_with_mass(d, 0.01, plant) - cost_with_mass(d, -0.01, plant)) / (0.02 * m);
  const json& rm = derivative_row(s, "cost", "mass");
  INFO("d cost / d mass (" << (plant ? "plant" : "design") << "): sensitivity " << rm.dump()
                           << ", independent " << dm);
  CHECK(std::abs(rm.at("derivative").get<double>() - dm) <=
        5.0 * rm.at("error").get<double>() + 1e-9 * std::abs(dm));
}

}  // namespace

TEST_CASE(
    "sensitivity of a committed design: files, finite elasticities, independent derivatives, "
    "thread-independent numbers",
    "[cli][sensitivity]") {
  TempDir dir("sensitivity_cli");
  const Run r = cli_support::pronk(
      dir, {"sensitivity", kDesign, "--out", "s1", "--samples", "4", "--threads", "2", "-q"});
  REQUIRE(r.code == 0);
  for (const char* f : {"sensitivity.json", "local.csv", "sobol.csv", "tornado.csv", "summary.md",
                        "report.html", "tornado.gp", "sobol.gp"}) {
    INFO(f);
    CHECK(!slurp(dir / ("s1/" + std::string(f))).empty());
  }
  const json s = json::parse(slurp(dir / "s1/sensitivity.json"));
  CHECK(s.at("model") == "impulse");
  CHECK(s.at("physical") == "plant");
  CHECK(s.at("failed_evaluations") == 0);
  // The ten tuned gains, the mass and the three principal moments (the impulse model uses
  // them; it has no leg stiffness or friction).
  std::vector<std::string> names;
  for (const json& in : s.at("inputs")) names.push_back(in.at("name"));
  CHECK(names.size() == 14);
  CHECK(std::count(names.begin(), names.end(), "mass") == 1);
  CHECK(std::count(names.begin(), names.end(), "inertia_zz") == 1);
  CHECK(std::count(names.begin(), names.end(), "leg_stiffness") == 0);
  // Every elasticity of the cost is finite (the cost is not 0).
  for (const json& row : s.at("local").at("derivatives")) {
    if (row.at("output") != "cost") continue;
    INFO(row.dump());
    CHECK(row.at("elasticity").is_number());
    CHECK(row.at("error").is_number());
  }
  const std::string local = slurp(dir / "s1/local.csv");
  CHECK(local.rfind("output,input,derivative,error,elasticity\n", 0) == 0);
  CHECK(slurp(dir / "s1/sobol.csv").rfind("output,input,S1,S1_lo,S1_hi,ST,ST_lo,ST_hi\n", 0) == 0);
  CHECK(std::count(local.begin(), local.end(), '\n') ==
        1 + 14 * static_cast<long>(s.at("outputs").size()));

  // The evaluation at the design is the recorded one.
  const json recorded = pronk::io::read_json_file(kDesign);
  CHECK(s.at("local").at("values").at("cost").get<double>() == recorded.at("cost").get<double>());

  // Independent central differences (step 1 %, the command's h) of the design's own evaluator.
  const pronk::optimize::RecordedDesign d = pronk::optimize::read_design(recorded, kDesign);
  const size_t j = 0;  // kp_x
  const double x = d.study.evaluator.parameters[j].from_unit(d.unit[j]);
  const double h = 1e-2 * x;
  const double dkp = (cost_with(d, j, x + h) - cost_with(d, j, x - h)) / (2 * h);
  const json& rk = derivative_row(s, "cost", d.study.evaluator.parameters[j].name);
  INFO("d cost / d kp_x: sensitivity " << rk.dump() << ", independent " << dkp);
  // The independent difference at step h errs about four times the estimate (of the h/2 one).
  CHECK(std::abs(rk.at("derivative").get<double>() - dkp) <=
        5.0 * rk.at("error").get<double>() + 1e-9 * std::abs(dkp));
  check_mass_derivative(s, d, true);

  // Physical numbers in robot and controller alike.
  const Run rd = cli_support::pronk(dir, {"sensitivity", kDesign, "--out", "s1d", "--samples", "0",
                                          "--threads", "2", "-q", "--physical", "design"});
  REQUIRE(rd.code == 0);
  const json sd = json::parse(slurp(dir / "s1d/sensitivity.json"));
  CHECK(sd.at("physical") == "design");
  CHECK(sd.at("sobol").is_null());
  check_mass_derivative(sd, d, false);

  // One thread: the same bits.
  const Run r1 = cli_support::pronk(
      dir, {"sensitivity", kDesign, "--out", "s1t", "--samples", "4", "--threads", "1", "-q"});
  REQUIRE(r1.code == 0);
  CHECK(slurp(dir / "s1t/local.csv") == local);
  CHECK(slurp(dir / "s1t/sobol.csv") == slurp(dir / "s1/sobol.csv"));
  CHECK(slurp(dir / "s1t/tornado.csv") == slurp(dir / "s1/tornado.csv"));
}

TEST_CASE("sensitivity: bad input exits 2 naming the option or the pointer", "[cli][sensitivity]") {
  TempDir dir("sensitivity_cli");
  auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"sensitivity", kDesign, "--out", "o", "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli_support::pronk(dir, args);
  };
  check_bad_input(run({"--range", "/body/mass=1.5"}),
                  "--range: /body/mass: expected a relative range in (0, 1)");
  check_bad_input(run({"--range", "mass=0.1"}), "--range: /: expected POINTER=REL");
  check_bad_input(run({"--range", "/body/nothing=0.1"}),
                  "--range: /body/nothing: expected a pointer to a number of the scene");
  check_bad_input(run({"--range", "/pseudo_rigid/leg_stiffness=0.1"}),
                  "--range: /pseudo_rigid/leg_stiffness: expected a number the model uses");
  check_bad_input(run({"--range", "/body/inertia_tensor/2/2=0.5"}),
                  "--range: /body/inertia_tensor: expected ranges of the principal moments");
  check_bad_input(run({"--inputs", "/body/nothing", "--samples", "0"}),
                  "--inputs: /body/nothing: expected a pointer to a number of the scene");
  check_bad_input(run({"--inputs", "/body/mass", "/body/mass"}),
                  "--inputs: /body/mass: expected each input once");
  check_bad_input(run({"--inputs", "/body/mass", "--range", "/body/inertia_tensor/0/0=0.01"}),
                  "--range: /body/inertia_tensor/0/0: expected one of the --inputs");
  check_bad_input(run({"--local-step", "0"}), "--local-step: /: expected a relative step");
  check_bad_input(run({"--samples", "1"}), "--samples: /: expected at least 2 base samples");
  check_bad_input(run({"--chart", "nope", "--samples", "0"}), "--chart: /: expected an output");
  // A design that is not one: the file and the pointer.
  write_file(dir / "bad.json", "{\"study\": 3}");
  const Run b = cli_support::pronk(dir, {"sensitivity", "bad.json", "-q"});
  CHECK(b.code == 2);
  CHECK_THAT(b.err, Contains("bad.json"));
}

#ifdef PRONK_MPIEXEC
TEST_CASE("sensitivity under mpirun -np 2: the files of one process", "[cli][sensitivity][mpi]") {
  TempDir dir("sensitivity_cli");
  const Run one = cli_support::pronk(
      dir, {"sensitivity", kDesign, "--out", "one", "--samples", "4", "--threads", "1", "-q"});
  REQUIRE(one.code == 0);
  std::string cmd = "cd " + quote(dir.path) + " && ASAN_OPTIONS=detect_leaks=0 ";
  cmd += PRONK_MPIEXEC;
  cmd += " -x ASAN_OPTIONS --allow-run-as-root --oversubscribe -np 2 ";
  cmd += quote(PRONK_EXE);
  cmd += " sensitivity ";
  cmd += quote(kDesign);
  cmd += " --out mpi --samples 4 -q >";
  cmd += quote(dir / ".mpi_out");
  cmd += " 2>&1";
  const int status = std::system(cmd.c_str());
  INFO(slurp(dir / ".mpi_out"));
  REQUIRE((status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0));
  for (const char* f : {"local.csv", "sobol.csv", "tornado.csv"}) {
    INFO(f);
    CHECK(slurp(dir / ("mpi/" + std::string(f))) == slurp(dir / ("one/" + std::string(f))));
  }
}
#endif
