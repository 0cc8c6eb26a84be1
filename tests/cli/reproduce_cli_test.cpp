// End-to-end `pronk reproduce`: its report in two parts (the trials' decisions, the values
// against their tolerances), its exit codes, and bad input as one line (exit 2): a mistyped
// or inconsistent design.json, --rtol that is not a finite number > 0.
#include <algorithm>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

// Study 2 cut to 6 evaluations (under a second with its perturbation run), in `d`/study2.
json recorded_study2(const TempDir& d) {
  const Run r = cli_support::pronk(
      d, {"optimize", std::string(PRONK_SOURCE_DIR) + "/studies/study2_legged_pulse_duty50.json",
          "-q", "--threads", "2", "--set", "/optimizer/max_evaluations=6", "--out", "study2"});
  REQUIRE(r.code == 0);
  return json::parse(slurp(d / "study2/design.json"));
}

void check_one_error_line(const Run& r, const std::string& starts) {
  CHECK(r.code == 2);
  CHECK_THAT(r.err, StartsWith("pronk: error: " + starts));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

std::string last_line(const std::string& text) {
  const size_t end = text.find_last_not_of('\n');
  const size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end - start);
}

}  // namespace

TEST_CASE("reproduce reports the decisions and the values apart, and exits by both",
          "[cli][reproduce]") {
  TempDir d("reproduce_cli");
  json design = recorded_study2(d);
  Run r = cli_support::pronk(d, {"reproduce", "study2/design.json", "--threads", "2"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("(a) decisions of 80 trials: identical"));
  CHECK_THAT(r.out, Contains("(b) values: the recording build: every value bit-identical"));
  CHECK_THAT(last_line(r.out), StartsWith("reproduced: 0 of "));
  CHECK_THAT(last_line(r.out), Contains("0 of 80 trial decisions differ"));

  // Recorded by another build, with one held-out trial's verdict and its fraction edited.
  design["commit"] = "0000000";
  json& t = design["validation"]["trials"][5];
  t["stabilized"] = !t["stabilized"].get<bool>();
  long n = 0;
  for (const auto& x : design["validation"]["trials"]) n += x["stabilized"].get<bool>() ? 1 : 0;
  design["validation"]["metrics"]["stabilized"] = static_cast<double>(n) / 64.0;
  write_file(d / "edited.json", design.dump());
  r = cli_support::pronk(d, {"reproduce", "edited.json", "--threads", "2"});
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("another build: each value within the tolerance the design records"));
  CHECK_THAT(r.out, Contains("(a) decisions of 80 trials: 1 differ"));
  CHECK_THAT(r.out, Contains("  validation 5 ("));
  CHECK_THAT(last_line(r.out), StartsWith("NOT REPRODUCED: 1 of "));
  CHECK_THAT(last_line(r.out), Contains("1 of 80 trial decisions differ"));
  // --scenarios-only leaves the validation set out (and says so).
  r = cli_support::pronk(d, {"reproduce", "edited.json", "--scenarios-only"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("the validation set is not re-evaluated (--scenarios-only)"));
  CHECK_THAT(r.out, Contains("(a) decisions of 16 trials: identical"));
}

TEST_CASE("reproduce: a mistyped or inconsistent design.json is one line, exit 2",
          "[cli][reproduce][input]") {
  TempDir d("reproduce_cli");
  const json design = recorded_study2(d);
  json bad = design;
  bad["metrics"]["y_error"] = "0.01";
  write_file(d / "typed.json", bad.dump());
  check_one_error_line(cli_support::pronk(d, {"reproduce", "typed.json"}),
                       "typed.json: /metrics/y_error: expected a finite number");
  bad = design;
  bad["validation"] = nullptr;  // the study has a held-out set: not to be skipped silently
  write_file(d / "novalidation.json", bad.dump());
  check_one_error_line(cli_support::pronk(d, {"reproduce", "novalidation.json"}),
                       "novalidation.json: /validation: expected the validation record");
  bad = design;
  bad["parameters"]["pulse_duration"] = 0.35;
  write_file(d / "params.json", bad.dump());
  check_one_error_line(cli_support::pronk(d, {"reproduce", "params.json"}),
                       "params.json: /parameters/pulse_duration: expected the value the design's "
                       "unit gives");
  for (const char* rtol : {"nan", "inf", "-1", "0", "1e-6x"}) {
    INFO(rtol);
    const Run r = cli_support::pronk(d, {"reproduce", "study2/design.json", "--rtol", rtol});
    check_one_error_line(r, "--rtol: /: expected a finite relative tolerance > 0, found ");
  }
  // A valid --rtol still forces the plain relative comparison.
  const Run r = cli_support::pronk(d, {"reproduce", "study2/design.json", "--rtol", "1e-9"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("(b) values: each value within rtol 1e-09"));
}
