// pagmo in a study (the shipped example, studies/study2_pagmo_cmaes.json): bad optimizer
// sections are input errors naming the pointer (exit 2), the journal is the same bytes
// with 1 and 2 threads, a run killed at a crash point (as kill -9 would) resumes to the
// uninterrupted run's journal and design, and the design reproduces.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/write/crash_point.hpp"
#include "optimize/study.hpp"
#include "tests/cli/cli_support.hpp"

using nlohmann::json;
using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

namespace {

const std::string kStudy = std::string(PRONK_SOURCE_DIR) + "/studies/study2_pagmo_cmaes.json";

/// The example study with `overrides` ("/ptr=value"); the InputError it raises, if any.
std::string load_error(const std::vector<std::string>& overrides, std::string* pointer) {
  try {
    (void)pronk::optimize::load_study(kStudy, overrides);
  } catch (const pronk::io::InputError& e) {
    *pointer = e.pointer();
    return e.what();
  }
  return "";
}

/// `pronk optimize` of the example made small: populations of 8, 40 evaluations.
Run optimize(const cli_support::TempDir& d, const std::string& out, const std::string& threads,
             bool resume = false) {
  std::vector<std::string> args = {"optimize",
                                   kStudy,
                                   "-q",
                                   "--threads",
                                   threads,
                                   "--set",
                                   "/optimizer/max_evaluations=40",
                                   "--set",
                                   "/optimizer/options/population=8",
                                   "--out",
                                   d / out};
  if (resume) args.push_back("--resume");
  return cli_support::pronk(d, args);
}

}  // namespace

TEST_CASE("pagmo studies: a bad optimizer section names its pointer", "[optimize][pagmo][input]") {
  std::string pointer;
  CHECK(load_error({}, &pointer).empty());
  CHECK_THAT(load_error({"/optimizer/algorithm=\"nsga9\""}, &pointer),
             Catch::EndsWith("/optimizer/algorithm: expected a pagmo algorithm pronk offers "
                             "(cmaes, xnes, de, sade, de1220, pso_gen), found \"nsga9\""));
  CHECK(pointer == "/optimizer/algorithm");
  CHECK_THAT(load_error({"/optimizer/options/sigma=0.2"}, &pointer),
             Catch::EndsWith("/optimizer/options/sigma: expected an option of pagmo cmaes "
                             "(population, generations, ftol, xtol, sigma0, cc, cs, c1, cmu), "
                             "found an unknown option"));
  CHECK_THAT(load_error({"/optimizer/options/population=4"}, &pointer),
             Catch::EndsWith("/optimizer/options/population: expected a population of at least "
                             "5 (pagmo cmaes needs at least 5 individuals), found 4"));
  CHECK(pointer == "/optimizer/options/population");
  CHECK_THAT(load_error({"/optimizer/algorithm=\"sade\"", "/optimizer/options={\"population\": 6}"},
                        &pointer),
             Catch::Contains("expected a population of at least 7"));
  CHECK_THAT(load_error({"/optimizer/xtol_rel=1e-4"}, &pointer),
             Catch::EndsWith("/optimizer/xtol_rel: expected no \"xtol_rel\" with library pagmo "
                             "(it takes no local algorithm and no derivatives; its tolerances "
                             "are options/ftol and options/xtol), found number 0.0001"));
  CHECK_THAT(load_error({"/optimizer/options=[]"}, &pointer),
             Catch::Contains("/optimizer/options: expected an object of pagmo options"));

  // The command line: exit 2, one line naming the study file, the pointer, what was expected
  // and what was found, for an unknown algorithm, an unknown option and a small population.
  cli_support::TempDir d("pagmo_study");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"/optimizer/algorithm=\"nsga9\"",
       "/optimizer/algorithm: expected a pagmo algorithm pronk offers (cmaes, xnes, de, sade, "
       "de1220, pso_gen), found \"nsga9\""},
      {"/optimizer/options/sigma=0.2",
       "/optimizer/options/sigma: expected an option of pagmo cmaes (population, generations, "
       "ftol, xtol, sigma0, cc, cs, c1, cmu), found an unknown option"},
      {"/optimizer/options/population=3",
       "/optimizer/options/population: expected a population of at least 5 (pagmo cmaes needs "
       "at least 5 individuals), found 3"},
  };
  for (const auto& [set, message] : cases) {
    const Run r = cli_support::pronk(d, {"optimize", kStudy, "--set", set, "--out", d / "out"});
    INFO(set);
    CHECK(r.code == 2);
    CHECK(r.err == "pronk: error: " + kStudy + ": " + message + "\n");
  }
  CHECK_FALSE(std::filesystem::exists(d / "out"));
}

TEST_CASE("pagmo studies: 1 and 2 threads write the same journal; kill -9 and --resume too",
          "[optimize][pagmo][journal][determinism]") {
  cli_support::TempDir d("pagmo_study");
  const Run one = optimize(d, "t1", "1");
  INFO(one.err);
  REQUIRE(one.code == 0);
  const Run two = optimize(d, "t2", "2");
  REQUIRE(two.code == 0);
  const std::string journal = slurp(d / "t1/journal.jsonl");
  CHECK(journal == slurp(d / "t2/journal.jsonl"));
  CHECK(std::count(journal.begin(), journal.end(), '\n') == 41);  // header + 5 populations of 8

  // Killed at crash points (PRONK_CRASH_AT, io/write/crash_point.hpp: std::_Exit as kill -9
  // would, some with half a journal line written): inside the second population, inside the
  // fourth, and at the last point (the result files); each run resumed on 1 thread ends with
  // the uninterrupted run's journal and design.
  ::setenv("PRONK_CRASH_AT", "0", 1);
  const Run counted = optimize(d, "count", "2");
  ::unsetenv("PRONK_CRASH_AT");
  REQUIRE(counted.code == 0);
  const long points = std::stol(counted.err.substr(counted.err.rfind(": ") + 2));
  REQUIRE(points > 41);  // at least one per journal line
  const json a = json::parse(slurp(d / "t1/design.json"));
  for (const long n : {15L, 33L, points}) {
    INFO("PRONK_CRASH_AT=" << n);
    const std::string out = "k" + std::to_string(n);
    ::setenv("PRONK_CRASH_AT", std::to_string(n).c_str(), 1);
    const Run killed = optimize(d, out, "2");
    ::unsetenv("PRONK_CRASH_AT");
    CHECK(killed.code == pronk::io::kCrashExitCode);
    const std::string partial = slurp(d / (out + "/journal.jsonl"));
    const std::string whole_lines = partial.substr(0, partial.rfind('\n') + 1);
    CHECK(journal.rfind(whole_lines, 0) == 0);  // a prefix of the uninterrupted journal

    const Run resumed = optimize(d, out, "1", true);
    INFO(resumed.err);
    REQUIRE(resumed.code == 0);
    CHECK(slurp(d / (out + "/journal.jsonl")) == journal);
    const json b = json::parse(slurp(d / (out + "/design.json")));
    for (const char* key : {"unit", "parameters", "cost", "constraints", "metrics", "validation"}) {
      INFO(key);
      CHECK(a.at(key) == b.at(key));
    }
  }
  CHECK(a.at("optimizer").at("library") == "pagmo");
  CHECK(a.at("optimizer").at("evaluations") == 40);

  // The design reproduces bit for bit on this build.
  const Run rep = cli_support::pronk(d, {"reproduce", d / "k15/design.json"});
  INFO(rep.out << rep.err);
  CHECK(rep.code == 0);
}
