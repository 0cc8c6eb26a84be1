// `pronk design`: from a robot scene to a design, the derived study written where a user can
// read and rerun it, the design reproduced, and its bad input.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_support.hpp"

using namespace cli_support;
using Catch::Matchers::Contains;

namespace {

// Built with += only: GCC 12 warns falsely (-Wstringop-overread) on std::string&& + "literal".
std::string tripod() {
  std::string path = PRONK_SOURCE_DIR;
  path += "/studies/scenes/family/tripod.json";
  return path;
}

// A small design (a few evaluations of short trials): the command's plumbing, not its result.
std::vector<std::string> small(const std::string& out, const std::string& model,
                               const std::string& budget = "3") {
  return {"design",    tripod(), "--out",    out, "--model",      model, "--pulse-budget", "4",
          "--budget",  budget,   "--trials", "2", "--validation", "2",   "--duration",     "2",
          "--threads", "2",      "-q"};
}

}  // namespace

TEST_CASE("pronk design writes the study it derives, runs it, and the design reproduces",
          "[cli][design]") {
  TempDir d("design");
  const Run r = pronk(d, small("tripod", "pseudo_rigid"));
  REQUIRE(r.code == 0);
  for (const char* f : {"study.json", "scene.json", "design.json", "summary.md", "report.html",
                        "stages/1_pulse/design.json", "stages/2_full/design.json"}) {
    INFO(f);
    CHECK(std::filesystem::exists(d / ("tripod/" + std::string(f))));
  }
  // The copy is the scene as given; the study names it.
  CHECK(nlohmann::json::parse(slurp(d / "tripod/scene.json")) ==
        nlohmann::json::parse(slurp(tripod())));
  const auto study = nlohmann::json::parse(slurp(d / "tripod/study.json"));
  CHECK(study.at("scene") == "scene.json");
  // The validation perturbs the robot, and the summary shows it beside the nominal robot.
  CHECK(study.at("validation").at("random").at("perturb").size() == 4);
  CHECK_THAT(slurp(d / "tripod/stages/2_full/summary.md"), Contains("nominal robot"));
  // pronk reproduce checks the design; pronk optimize reruns the study to the same journal.
  const Run rep = pronk(d, {"reproduce", "tripod/design.json", "--threads", "1"});
  CHECK(rep.code == 0);
  const Run again =
      pronk(d, {"optimize", "tripod/study.json", "--out", "again", "--threads", "1", "-q"});
  REQUIRE(again.code == 0);
  CHECK(slurp(d / "again/stages/2_full/journal.jsonl") ==
        slurp(d / "tripod/stages/2_full/journal.jsonl"));
}

TEST_CASE("pronk design --study-only, --resume, and a directory that holds a design",
          "[cli][design]") {
  TempDir d("design_resume");
  std::vector<std::string> args = small("out", "pulse");
  args.push_back("--study-only");
  REQUIRE(pronk(d, args).code == 0);
  CHECK(std::filesystem::exists(d / "out/study.json"));
  CHECK_FALSE(std::filesystem::exists(d / "out/design.json"));
  // Without --resume the directory that holds a design study is refused; with it, the same
  // options continue it.
  check_bad_input(pronk(d, small("out", "pulse")),
                  "--out: /: expected a directory without a design");
  std::vector<std::string> resume = small("out", "pulse");
  resume.push_back("--resume");
  CHECK(pronk(d, resume).code == 0);
  CHECK(std::filesystem::exists(d / "out/design.json"));
  // Other options derive another study: refused on --resume.
  resume[resume.size() - 5] = "3";  // --duration 3
  check_bad_input(pronk(d, resume), "out/study.json: /: expected the study these options");
}

TEST_CASE("pronk design: a scene without legs and bad options are exit 2", "[cli][design]") {
  TempDir d("design_bad");
  write_file(d / "ball.json", R"({"body": {"mass": 1}, "legs": {"kind": "body_only"}})");
  check_bad_input(pronk(d, {"design", "ball.json", "--out", "o"}),
                  "ball.json: /legs/kind: expected a legged robot");
  check_bad_input(pronk(d, {"design", tripod(), "--out", "o", "--duty", "0.3,0.2"}),
                  "--duty: /: expected a valid design option");
  check_bad_input(pronk(d, {"design", tripod(), "--out", "o", "--perturb", "1.5,0,0"}),
                  "--perturb: /: expected a valid design option");
}

TEST_CASE("pronk design --optimizer cmaes runs the full stage on pagmo's CMA-ES", "[cli][design]") {
  TempDir d("design_cmaes");
  std::vector<std::string> args = small("c", "pseudo_rigid", "10");  // two generations of 5
  for (const char* a : {"--optimizer", "cmaes", "--population", "5"}) args.push_back(a);
  REQUIRE(pronk(d, args).code == 0);
  const auto design = nlohmann::json::parse(slurp(d / "c/stages/2_full/design.json"));
  CHECK(design.at("optimizer").at("library") == "pagmo");
  CHECK(design.at("optimizer").at("algorithm") == "cmaes");
  CHECK(design.at("optimizer").at("evaluations").get<long>() <= 10);
  check_bad_input(
      pronk(d, {"design", tripod(), "--out", "o", "--optimizer", "cmaes", "--population", "4"}),
      "command line: /: expected options");
}
