// End-to-end hardening: inputs that used to crash pronk or end as internal
// failures are bad input (exit 2, one line naming the file and where): deeply
// nested JSON, directories given as files, --out paths that cannot be a
// directory, out-of-range physical numbers. And max_steps bounds a whole run.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"
#include "tests/optimize/map/map_test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

const std::string kStudies = std::string(PRONK_SOURCE_DIR) + "/studies/";

}  // namespace

TEST_CASE("100000 levels of nesting are bad input for every command, not a stack overflow",
          "[cli][hardening]") {
  TempDir d("hardening");
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  write_file(d / "deep.json", deep);
  write_file(d / "open.json", std::string(100000, '{'));
  for (const std::vector<std::string>& args : {std::vector<std::string>{"simulate", "deep.json"},
                                               {"optimize", "deep.json"},
                                               {"map", "deep.json"},
                                               {"reproduce", "deep.json"},
                                               {"simulate", "open.json"}}) {
    INFO(args[0] << " " << args[1]);
    const Run r = cli_support::pronk(d, args);
    check_bad_input(r, args[1] + ": /: expected JSON nested at most 128 levels deep");
    CHECK_THAT(r.err, Contains("found arrays/objects nested 100000 levels deep"));
  }
  // Brackets inside strings are not nesting: the scene loader reports the real problem.
  write_file(d / "string.json", "{\"nmae\": \"\\\"" + std::string(1000, '[') + "\"}");
  check_bad_input(cli_support::pronk(d, {"simulate", "string.json"}),
                  "string.json: /nmae: expected a known key");
  // --set values are bounded too.
  check_bad_input(cli_support::pronk(d, {"simulate", kStudies + "scenes/case1_body_only.json",
                                         "--set", "/body/mass=" + std::string(100000, '[')}),
                  "command line (--set /body/mass=");
}

TEST_CASE("a directory given as an input file is bad input", "[cli][hardening]") {
  TempDir d("hardening");
  fs::create_directory(d / "dir.json");
  for (const char* cmd : {"simulate", "optimize", "map", "reproduce"}) {
    INFO(cmd);
    check_bad_input(cli_support::pronk(d, {cmd, "dir.json"}),
                    "dir.json: /: expected a JSON file, found a directory");
  }
  json study = json::parse(slurp(kStudies + "study1_body_only_gains.json"));
  study["scene"] = d / "dir.json";
  write_file(d / "study.json", study.dump());
  check_bad_input(cli_support::pronk(d, {"optimize", "study.json"}),
                  d / "dir.json" + ": /: expected a JSON file");
}

TEST_CASE("an --out that cannot be a directory is bad input, before any work", "[cli][hardening]") {
  TempDir d("hardening");
  write_file(d / "file", "x");
  json map = ::pronk::test::tiny_map_document();
  write_file(d / "map.json", map.dump());
  const std::string scene = kStudies + "scenes/case1_body_only.json";
  const std::vector<std::vector<std::string>> commands = {
      {"simulate", scene},
      {"simulate", kStudies + "mechanisms/pendulum.json"},
      {"optimize", kStudies + "study1_body_only_gains.json"},
      {"map", "map.json"},
      {"bench", "--quick"}};
  for (const std::string& out : {d / "file/x", d / "file"}) {
    for (std::vector<std::string> args : commands) {
      args.insert(args.end(), {"--out", out});
      INFO(args[0] << " --out " << out);
      const Run r = cli_support::pronk(d, args);
      check_bad_input(r, "--out: /: expected a directory that exists or can be created, found \"" +
                             d / "file\"");
    }
  }
  // A default output directory that cannot be created is bad input too.
  write_file(d / "out", "a file where pronk puts its outputs");
  check_bad_input(cli_support::pronk(d, {"simulate", scene, "--set", "/simulation/duration=0.5"}),
                  "out/case1_body_only: /: expected a directory that exists or can be created");
}

TEST_CASE("out-of-range physical numbers are bad input with their pointer", "[cli][hardening]") {
  TempDir d("hardening");
  json mech = json::parse(slurp(kStudies + "mechanisms/satellite.json"));
  mech["bodies"][0]["mass"] = 1e308;
  write_file(d / "mech.json", mech.dump());
  check_bad_input(cli_support::pronk(d, {"simulate", "mech.json"}),
                  "mech.json: /bodies/0/mass: expected a finite number in [1e-06, 1000000]");
  const std::string scene = kStudies + "scenes/case1_body_only.json";
  check_bad_input(cli_support::pronk(d, {"simulate", scene, "--set", "/body/mass=1e308"}),
                  scene + ": /body/mass: expected a finite number in [1e-06, 1000000]");
  check_bad_input(cli_support::pronk(d, {"simulate", scene, "--set", "/legs/length=1e300"}),
                  scene + ": /legs/length: expected a finite number > 0 and <= 1e+12");
  check_bad_input(cli_support::pronk(d, {"simulate", kStudies + "mechanisms/spring_leg_drop.json",
                                         "--set", "/connections/0/stiffness=1e200"}),
                  kStudies +
                      "mechanisms/spring_leg_drop.json: /connections/0/stiffness: expected "
                      "a finite number in [0, 1e+12]");
}

TEST_CASE("max_steps bounds the whole run across restarts, ending it with a reason",
          "[cli][hardening]") {
  TempDir d("hardening");
  // Case 1 with RK4 at 1 ms: ~10000 steps over 10 s, each hop's flight and stance far
  // below 2000 steps, so only a budget over the whole run stops it.
  const Run r =
      cli_support::pronk(d, {"simulate", kStudies + "scenes/case1_body_only.json", "--set",
                             "/simulation/solver={\"method\": \"rk4\", \"h_fixed\": 0.001, "
                             "\"max_steps\": 2000}",
                             "--out", "o", "-q"});
  CHECK(r.code == 1);
  const json summary = json::parse(slurp(d / "o/summary.json"));
  CHECK(summary["status"] == "diverged");
  CHECK_THAT(summary["reason"].get<std::string>(),
             StartsWith("step budget exceeded: 2000 step attempts"));
  CHECK(summary["cost"]["steps_accepted"].get<long>() +
            summary["cost"]["steps_rejected"].get<long>() ==
        2000);
  CHECK(summary["t_end"].get<double>() == Approx(2.0).margin(0.05));
  // The pseudo-rigid mechanism simulator and the robot in the full model count the same way.
  const Run m = cli_support::pronk(d, {"simulate", kStudies + "mechanisms/spring_leg_drop.json",
                                       "--set", "/simulation/max_steps=300", "--out", "m", "-q"});
  CHECK(m.code == 1);
  CHECK_THAT(slurp(d / "m/summary.json"), Contains("reached max_steps = 300 at t = "));
  const Run p =
      cli_support::pronk(d, {"simulate", kStudies + "scenes/case5_pr_hop_height.json", "--set",
                             "/pseudo_rigid/solver={\"max_steps\": 300}", "--out", "p", "-q"});
  CHECK(p.code == 1);
  CHECK_THAT(slurp(d / "p/summary.json"), Contains("reached max_steps = 300 at t = "));
}
