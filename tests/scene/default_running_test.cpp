// Defaults that run: three legged robots of 0.5, 1.5 and 5 kg, each scene giving only its
// body, its legs, a hop height and a speed, hop stably in the pulse model with the lateral
// loop the defaults close (banking with roll and bank gains placed on each robot's stride).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/load/scene_loader.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/simulate.hpp"

using namespace pronk;
using nlohmann::json;

namespace {

struct Robot {
  const char* name;
  const char* scene;
};

// Issue 35's three-legged robot; a 0.5 kg quadruped; a 5 kg hexapod with a 2.5:1 inertia
// ratio, 0.4 m hops at 0.6 m/s.
const Robot kRobots[] = {
    {"three legs, 1.5 kg", R"({
      "body": {"mass": 1.5, "inertia": [0.006, 0.009, 0.012]},
      "legs": {"kind": "legged", "hips": [[0.15, 0, -0.04], [-0.08, 0.13, -0.04], [-0.08, -0.13, -0.04]]},
      "controller": {"hop_height": 0.3, "setpoint": {"velocity": [0.4, 0, 0]}}})"},
    {"four legs, 0.5 kg", R"({
      "body": {"mass": 0.5, "inertia": [0.0008, 0.0012, 0.0018]},
      "legs": {"kind": "legged", "length": 0.15,
               "hips": [[0.07, 0.05, -0.02], [0.07, -0.05, -0.02], [-0.07, 0.05, -0.02], [-0.07, -0.05, -0.02]]},
      "controller": {"hop_height": 0.15, "setpoint": {"velocity": [0.2, 0, 0]}}})"},
    {"six legs, 5 kg", R"({
      "body": {"mass": 5, "inertia": [0.04, 0.1, 0.12]},
      "legs": {"kind": "legged", "length": 0.35,
               "hips": [[0.2, 0.12, -0.05], [0.2, -0.12, -0.05], [0, 0.14, -0.05], [0, -0.14, -0.05],
                        [-0.2, 0.12, -0.05], [-0.2, -0.12, -0.05]]},
      "controller": {"hop_height": 0.4, "setpoint": {"velocity": [0.6, 0, 0]}}})"},
};

// The robot in the pulse model for 20 s from `initial`.
scene::Scene robot_scene(const Robot& r, const json& initial) {
  json doc = json::parse(r.scene);
  doc["model"] = "pulse";
  doc["initial"] = initial;
  doc["simulation"] = {{"duration", 20}};
  return io::parse_scene(doc, r.name);
}

// Largest |y - y_d| over the trajectory samples [m].
double max_lateral_error(const reduced::RunResult& run) {
  double m = 0.0;
  for (const auto& s : run.trajectory) m = std::max(m, std::abs(s.position.y() - s.setpoint.y()));
  return m;
}

}  // namespace

TEST_CASE("legged robots of 0.5 to 5 kg hop stably on the defaults in the pulse model",
          "[scene][defaults]") {
  for (const Robot& r : kRobots) {
    INFO(r.name);
    // 5 cm to the side of the setpoint, level: settles within 12 strides (measured: 10 for
    // each), and never strays more than 0.1 m laterally in 20 s.
    const scene::Scene s = robot_scene(r, {{"position", {0, 0.05, 0.5}}});
    REQUIRE(s.controller.bank_enabled);
    const RunResult res = simulate(s);
    REQUIRE(res.run.status == reduced::RunStatus::kCompleted);
    const reduced::RunMetrics m = reduced::compute_metrics(s, res.run);
    CHECK(m.settle_strides >= 0);
    CHECK(m.settle_strides <= 12);
    CHECK(max_lateral_error(res.run) <= 0.1);
    CHECK(std::abs(m.final_y_error) < 1e-3);
    // Landing with 5 deg of roll: the tilted first stance throws the robot sideways (up to
    // 0.96 m for the 5 kg robot), and the loop brings it back: settled within 25 strides
    // (measured: 21, 19, 22).
    const scene::Scene tilted =
        robot_scene(r, {{"position", {0, 0, 0.5}}, {"attitude_deg", {5, 0, 0}}});
    const RunResult rt = simulate(tilted);
    REQUIRE(rt.run.status == reduced::RunStatus::kCompleted);
    const reduced::RunMetrics mt = reduced::compute_metrics(tilted, rt.run);
    CHECK(mt.settle_strides >= 0);
    CHECK(mt.settle_strides <= 25);
    CHECK(std::abs(mt.final_y_error) < 0.01);
  }
}

TEST_CASE("without banking the three-legged robot loses its setpoint by metres",
          "[scene][defaults]") {
  // The reference: the scene format's old default (banking off) from the same 5 deg landing.
  json doc = json::parse(kRobots[0].scene);
  doc["model"] = "pulse";
  doc["controller"]["bank"] = {{"enabled", false}};
  doc["initial"] = {{"position", {0, 0, 0.5}}, {"attitude_deg", {5, 0, 0}}};
  doc["simulation"] = {{"duration", 20}};
  const scene::Scene s = io::parse_scene(doc, "three legs");
  const RunResult res = simulate(s);
  REQUIRE(res.run.status == reduced::RunStatus::kCompleted);
  CHECK(std::abs(reduced::compute_metrics(s, res.run).final_y_error) > 3.0);
}

TEST_CASE("the shipped robots' bare scenes run on the full model's defaults",
          "[scene][defaults][pseudo_rigid]") {
  // Each scene gives only body, legs, hop height and speed; run as written in the full model
  // (default start at the apex, 20 % duty, damped legs, placed position loop) for its 10 s.
  // Measured: all complete; the 0.5 kg quadruped, the pentapod and pr_running's robot settle
  // (from stride 7 of 26, 0 of 18, 10 of 20), the hexapod only at its 13th of 14 (not
  // required here: a margin of one stride); the tripod and the sidestepping quadruped end
  // within 2 cm of the setpoint, not settled.
  const std::string dir = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/";
  const struct {
    const char* file;
    bool settles;
  } kScenes[] = {{"family/mini_quad.json", true}, {"family/pentapod.json", true},
                 {"family/hexapod.json", false},  {"pr_running_robot.json", true},
                 {"family/tripod.json", false},   {"family/sidestep_quad.json", false}};
  for (const auto& c : kScenes) {
    INFO(c.file);
    json doc = io::read_json_file(dir + c.file);
    doc["model"] = "pseudo_rigid";
    const scene::Scene s = io::parse_scene(doc, c.file);
    const RunResult res = simulate(s);
    REQUIRE(res.run.status == reduced::RunStatus::kCompleted);
    const reduced::RunMetrics m = reduced::compute_metrics(s, res.run);
    CHECK(std::hypot(m.final_x_error, m.final_y_error) < 0.03);
    if (c.settles) CHECK(m.settle_strides >= 0);
  }
}
