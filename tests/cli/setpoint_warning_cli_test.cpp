// `completed` is not the whole story: a run that completes far from its setpoint, or never
// settles, says so in summary.json (warnings far_from_setpoint, never_settled) and on the
// terminal, with the distance.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_support.hpp"

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

// Issue 35's three-legged robot in the pulse model, started 0.4 m to the side with 10 deg of
// roll, for 20 s.
const char* kThreeLegs = R"({
  "name": "three_legs",
  "model": "pulse",
  "body": {"mass": 1.5, "inertia": [0.006, 0.009, 0.012]},
  "legs": {"kind": "legged", "hips": [[0.15, 0, -0.04], [-0.08, 0.13, -0.04], [-0.08, -0.13, -0.04]]},
  "controller": {"hop_height": 0.3, "setpoint": {"velocity": [0.4, 0, 0]}},
  "initial": {"position": [0, 0.4, 0.27], "attitude_deg": [10, 0, 0]},
  "simulation": {"duration": 20}
})";

}  // namespace

TEST_CASE("a run that completes far from its setpoint warns in summary.json and on the terminal",
          "[cli][outputs]") {
  TempDir dir("setpoint");
  write_file(dir / "three_legs.json", kThreeLegs);
  // Banking off, as the scene format's default was: nothing closes the lateral loop.
  const Run far = pronk(dir, {"simulate", "three_legs.json", "--set",
                              R"(/controller/bank={"enabled": false})", "--out", "far"});
  REQUIRE(far.code == 0);  // it completed
  const json s = json::parse(slurp(dir / "far/summary.json"));
  CHECK(s["status"] == "completed");
  const double distance = std::hypot(s["metrics"]["final_x_error_m"].get<double>(),
                                     s["metrics"]["final_y_error_m"].get<double>());
  CHECK(distance > 10 * 0.3);
  CHECK(s["warnings"]["far_from_setpoint"] == 1);
  CHECK(s["warnings"]["never_settled"] == 1);
  char line[128];
  std::snprintf(line, sizeof line, "warning: far from the setpoint: ended %.3g m from it (%.1f",
                distance, distance / 0.3);
  CHECK_THAT(far.out, Contains(line));
  CHECK_THAT(far.out, Contains("warning: never settled"));

  // The default lateral loop (banking on, gains scaled to the robot) brings it back: neither.
  const Run home = pronk(dir, {"simulate", "three_legs.json", "--out", "home"});
  REQUIRE(home.code == 0);
  const json h = json::parse(slurp(dir / "home/summary.json"));
  CHECK(h["metrics"]["settle_strides"].get<long>() >= 0);
  CHECK(h["warnings"] == json::object());
  CHECK_THAT(home.out, !Contains("warning"));

  // A run too short to settle: only never_settled.
  const Run brief = pronk(dir, {"simulate", "three_legs.json", "--set", "/simulation/duration=2",
                                "--out", "brief", "-q"});
  REQUIRE(brief.code == 0);
  CHECK(brief.out.empty());  // -q prints nothing
  const json b = json::parse(slurp(dir / "brief/summary.json"));
  CHECK(b["warnings"] == json({{"never_settled", 1}}));
}
