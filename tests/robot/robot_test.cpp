// The robot in the full (pseudo-rigid) model against the seed's reference
// cases (Ridgely 2001, figs. 2.9-2.13), energy balance, and the reduced models of the
// same robot (fidelity agreement at ~15 % duty cycle).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/model.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/robot/robot_simulator.hpp"

using namespace pronk;

namespace {

constexpr double kDeg = M_PI / 180.0;

scene::Scene load(const std::string& name, const std::vector<std::string>& set = {}) {
  return io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + name, set);
}

}  // namespace

TEST_CASE("robot case 5: ghost-point hips, fixed-duration pulses, reaches and holds the hop height",
          "[robot]") {
  const scene::Scene s = load("case5_pr_hop_height.json");
  const robot::RobotRunResult r = robot::simulate(s);
  REQUIRE(r.run.status == reduced::RunStatus::kCompleted);
  const double target = s.legs.length + s.controller.hop_height;  // apex [m]
  REQUIRE(s.initial.position.z() < target - 0.1);                 // dropped below it
  const auto& st = r.run.strides;
  REQUIRE(st.size() >= 8);
  // Within 5 hops the apex is within 2 % of the hop height, and it stays there.
  long reached = -1;
  for (size_t k = 0; k < st.size(); ++k) {
    if (st[k].has_apex && std::abs(st[k].apex_height - target) <= 0.02 * s.controller.hop_height) {
      reached = static_cast<long>(k);
      break;
    }
  }
  REQUIRE(reached >= 0);
  CHECK(reached < 5);
  for (size_t k = static_cast<size_t>(reached); k < st.size(); ++k) {
    if (st[k].has_apex)
      CHECK(std::abs(st[k].apex_height - target) <= 0.02 * s.controller.hop_height);
  }
  // Energy balance (actuator work included) holds to the budget of auto, the default solver.
  CHECK(r.monitors.energy_drift <= s.pseudo_rigid.accuracy * r.monitors.energy_scale);
  // The same robot in the pulse model: the body-level motion agrees.
  scene::Scene p = s;
  p.model = scene::ModelKind::kPulse;
  const reduced::RunResult rp = reduced::simulate(p);
  REQUIRE(rp.strides.size() >= st.size() - 1);
  for (size_t k = 0; k + 1 < st.size(); ++k) {
    CHECK(std::abs(st[k].apex_height - rp.strides[k].apex_height) < 1e-4);
  }
}

TEST_CASE("robot case 6: leg-spring drop test conserves energy, apex heights stay",
          "[robot][heavy]") {
  const scene::Scene s = load("case6_pr_drop.json");
  const robot::RobotRunResult r = robot::simulate(s);
  REQUIRE(r.run.status == reduced::RunStatus::kCompleted);
  // Drop energy: the whole robot falls 0.15 m before the feet touch.
  double mass = s.body.mass + 4 * s.pseudo_rigid.foot_mass;
  const double drop = mass * s.gravity * (s.initial.position.z() - s.legs.length);
  CHECK(r.monitors.energy_drift <= 1e-3 * drop);
  const auto& st = r.run.strides;
  REQUIRE(st.size() >= 10);
  REQUIRE(st[0].has_apex);
  // First rebound: back to (nearly) the drop height; only the plastic foot impact is lost.
  CHECK(std::abs(st[0].apex_height - s.initial.position.z()) < 0.01);
  for (size_t k = 0; k < 10; ++k) {
    REQUIRE(st[k].has_apex);
    CHECK(std::abs(st[k].apex_height - st[0].apex_height) <= 0.03 * st[0].apex_height);
  }
  // Passive legs: the controller never pushed.
  for (const auto& f : r.stride_actuator_force) {
    for (double x : f) CHECK(x == 0.0);
  }
  // The feet vibrate on their leg springs (reported) and the pseudo-rigid body held.
  CHECK(r.monitors.max_leg_vibration_energy > 0.0);
  CHECK(r.monitors.max_strain < 0.01);
  CHECK(r.monitors.max_penetration < 0.005);
}

TEST_CASE("robot case 7: hop-height change settles, foot forces lower then raise",
          "[robot][heavy]") {
  const scene::Scene s = load("case7_pr_height_change.json");
  const robot::RobotRunResult r = robot::simulate(s);
  REQUIRE(r.run.status == reduced::RunStatus::kCompleted);
  const auto& st = r.run.strides;
  const double t_change = s.controller.hop_height_changes.at(0).first;
  const double h2 = s.controller.hop_height_changes.at(0).second;
  size_t first_after = 0;
  while (first_after < st.size() && st[first_after].t_touchdown < t_change) ++first_after;
  REQUIRE(first_after >= 1);
  // Lowering from the 0.15 m drop to 0.1 m: the actuators push down (negative).
  for (size_t k = 0; k < first_after; ++k) {
    for (double f : r.stride_actuator_force[k]) CHECK(f < 0.0);
  }
  // Raising to 0.2 m: they push up.
  for (size_t k = first_after; k < first_after + 3 && k < st.size(); ++k) {
    for (double f : r.stride_actuator_force[k]) CHECK(f > 0.0);
  }
  // Settled within 6 hops to within 5 % of the new hop height.
  const size_t sixth = first_after + 5;
  REQUIRE(sixth < st.size());
  for (size_t k = sixth; k < st.size(); ++k) {
    if (st[k].has_apex) CHECK(std::abs(st[k].apex_height - s.legs.length - h2) <= 0.05 * h2);
  }
  CHECK(r.monitors.energy_drift <= 1e-3 * r.monitors.energy_scale);
}

TEST_CASE("robot fidelity: pulse and pseudo-rigid strides agree at 15 % duty", "[robot]") {
  const scene::Scene s = load("fidelity_duty15.json");
  scene::Scene p = s;
  p.model = scene::ModelKind::kPulse;
  const reduced::RunResult rp = reduced::simulate(p);
  const robot::RobotRunResult rr = robot::simulate(s);
  REQUIRE(rp.status == reduced::RunStatus::kCompleted);
  REQUIRE(rr.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(rr.run.strides.size() == rp.strides.size());
  double apex = 0.0, attitude = 0.0, duty = 0.0;
  for (size_t k = 0; k < rp.strides.size(); ++k) {
    const auto &a = rp.strides[k], &b = rr.run.strides[k];
    if (a.has_apex && b.has_apex) apex = std::max(apex, std::abs(a.apex_height - b.apex_height));
    attitude = std::max(attitude, (a.euler123 - b.euler123).cwiseAbs().maxCoeff());
    if (a.stride_time > 0) duty = std::max(duty, a.duty_cycle);
  }
  INFO("apex " << apex << " m, attitude " << attitude / kDeg << " deg, duty " << duty);
  CHECK(duty > 0.13);
  CHECK(duty < 0.17);
  // Measured (internal k = 1e6 N/m): apex 1.3e-5 m, attitude 0.30 deg (pitch, the
  // body's flex under the hip forces; 0.03 deg with "auto" stiffness).
  CHECK(apex < 1e-4);
  CHECK(attitude < 0.5 * kDeg);
}

TEST_CASE("robot impulse feedback keeps a saturated actuator on until the impulse is delivered",
          "[robot]") {
  // Case 5 needs about 29 N per leg for 50 ms pulses; limit the actuators to 20 N.
  const scene::Scene open_loop =
      load("case5_pr_hop_height.json",
           {"/pseudo_rigid/actuator_max_force=20", "/simulation/duration=2.5"});
  const scene::Scene closed =
      load("case5_pr_hop_height.json",
           {"/pseudo_rigid/actuator_max_force=20", "/pseudo_rigid/impulse_feedback=true",
            "/simulation/duration=2.5"});
  const robot::RobotRunResult a = robot::simulate(open_loop);
  const robot::RobotRunResult b = robot::simulate(closed);
  REQUIRE(a.run.strides.size() >= 3);
  REQUIRE(b.run.strides.size() >= 3);
  const double target = closed.legs.length + closed.controller.hop_height;
  CHECK(a.run.warnings.at("actuator_saturated") > 0);
  // Closed loop: the delivered vertical impulse matches the request; open loop falls short.
  const auto& sb = b.run.strides[2];
  CHECK(std::abs(sb.apex_height - target) < 0.01);
  CHECK(a.run.strides[1].apex_height < target - 0.02);
  CHECK(sb.stance_duration > closed.pulse.duration);
}

TEST_CASE("robot scene: pseudo_rigid settings load, round-trip and are listed as unused",
          "[robot]") {
  const scene::Scene s = load("case6_pr_drop.json");
  CHECK(s.model == scene::ModelKind::kPseudoRigid);
  CHECK(s.pseudo_rigid.leg_stiffness == 100.0);
  const scene::Scene back = io::parse_scene(io::scene_to_json(s), "resolved");
  CHECK(io::scene_to_json(back) == io::scene_to_json(s));
  scene::Scene imp = s;
  imp.model = scene::ModelKind::kImpulse;
  const auto unused = io::unused_settings(imp);
  CHECK(std::find(unused.begin(), unused.end(), "/pseudo_rigid") != unused.end());
  const auto pr_unused = io::unused_settings(s);
  CHECK(std::find(pr_unused.begin(), pr_unused.end(), "/pseudo_rigid") == pr_unused.end());
  // Level feet act where the hips place the legs (hip_rotation): listed as unused without.
  CHECK(!s.pseudo_rigid.hip_rotation);
  CHECK(std::find(pr_unused.begin(), pr_unused.end(), "/pseudo_rigid/level_feet") !=
        pr_unused.end());
  const auto run_unused = io::unused_settings(load("pr_running.json"));
  CHECK(std::find(run_unused.begin(), run_unused.end(), "/pseudo_rigid/level_feet") ==
        run_unused.end());
  // "auto" stiffness.
  const scene::Scene a = load("case6_pr_drop.json", {"/pseudo_rigid/internal_stiffness=\"auto\""});
  CHECK(a.pseudo_rigid.internal_auto);
  // Errors name the pointer, expected and found.
  try {
    load("case6_pr_drop.json", {"/pseudo_rigid/leg_stifness=5"});
    FAIL("unknown key accepted");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()).find("/pseudo_rigid/leg_stifness") != std::string::npos);
  }
  try {
    load("case6_pr_drop.json", {"/pseudo_rigid/contact_stiffness=\"soft\""});
    FAIL("bad stiffness accepted");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()).find("/pseudo_rigid/contact_stiffness") != std::string::npos);
  }
}

// The robot's energy blow-up factor is the mechanisms' setting (pseudorigid
// SimulationOptions::energy_blowup_factor): the same default, read and validated by the scene
// loader, carried into the robot's mechanism; a small one ends the run `diverged` naming it.
TEST_CASE("robot pseudo_rigid energy_blowup_factor: default, validated, ends a run diverged",
          "[robot]") {
  CHECK(scene::PseudoRigid{}.energy_blowup_factor ==
        pseudorigid::SimulationOptions{}.energy_blowup_factor);
  const scene::Scene s = load("case5_pr_hop_height.json", {"/pseudo_rigid/energy_blowup_factor=3"});
  CHECK(s.pseudo_rigid.energy_blowup_factor == 3.0);
  CHECK(robot::build_robot(s).mechanism.simulation.energy_blowup_factor == 3.0);
  const nlohmann::json back = io::scene_to_json(s);
  CHECK(back["pseudo_rigid"]["energy_blowup_factor"] == 3.0);
  CHECK(io::scene_to_json(io::parse_scene(back, "resolved")) == back);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"0", "number 0"}, {"-2", "number -2"}, {"\"big\"", "string \"big\""}};
  for (const auto& [value, found] : bad) {
    try {
      load("case5_pr_hop_height.json", {"/pseudo_rigid/energy_blowup_factor=" + value});
      FAIL("energy_blowup_factor " << value << " accepted");
    } catch (const io::InputError& e) {
      INFO(e.what());
      CHECK(e.file().find("case5_pr_hop_height.json") != std::string::npos);
      CHECK(e.pointer() == "/pseudo_rigid/energy_blowup_factor");
      CHECK(e.expected() == "a finite number > 0 and <= 1e+12");
      CHECK(e.found() == found);
    }
  }
  // The four-mass body's balance drifts by ~7e-8 J over 0.5 s (scale 7.4 J): far below 10 x
  // the scale, far above 1e-12 x the scale. The reason names a factor the scene set (not the
  // default: the reasons of default runs stay as they were).
  const robot::RobotRunResult ok =
      robot::simulate(load("case5_pr_hop_height.json",
                           {"/simulation/duration=0.5", "/pseudo_rigid/body=\"four_masses\""}));
  REQUIRE(ok.run.status == reduced::RunStatus::kCompleted);
  const robot::RobotRunResult r = robot::simulate(load(
      "case5_pr_hop_height.json", {"/simulation/duration=0.5", "/pseudo_rigid/body=\"four_masses\"",
                                   "/pseudo_rigid/energy_blowup_factor=1e-12"}));
  INFO(r.run.reason);
  CHECK(r.run.status == reduced::RunStatus::kDiverged);
  CHECK(r.run.reason.find("energy blow-up") != std::string::npos);
  CHECK(r.run.reason.find("energy_blowup_factor 1e-12") != std::string::npos);
  CHECK(ok.run.reason.find("energy_blowup_factor") == std::string::npos);
  CHECK(r.run.t_end < 0.5);
}

TEST_CASE("robot hips as dummy masses (Ridgely 2001, §4.3) hop like ghost-point hips",
          "[robot][heavy]") {
  const scene::Scene g = load("case5_pr_hop_height.json", {"/simulation/duration=2.5"});
  const scene::Scene d = load("case5_pr_hop_height.json",
                              {"/simulation/duration=2.5", "/pseudo_rigid/hips=\"dummy_masses\""});
  const robot::RobotRunResult rg = robot::simulate(g);
  const robot::RobotRunResult rd = robot::simulate(d);
  REQUIRE(rd.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(rd.run.strides.size() == rg.run.strides.size());
  // Measured: dummy-mass hips settle 5.9 mm above the ghost-point hips' 0.45 m (the
  // ties' vibration under the pulses); energy balance 1.6e-4 of the scale on auto's choice
  // (DOPRI5 at 1e-6, rule 8), within its budget of 1e-3.
  for (size_t k = 0; k < rd.run.strides.size(); ++k) {
    if (!rd.run.strides[k].has_apex) continue;
    CHECK(std::abs(rd.run.strides[k].apex_height - rg.run.strides[k].apex_height) < 0.01);
  }
  CHECK(rd.monitors.energy_drift <= d.pseudo_rigid.accuracy * rd.monitors.energy_scale);
}

// Issue 4's running criterion: from 10 deg roll and 0.2 m lateral offset the full
// model runs after a setpoint moving at 0.3 m/s for 10 s without falling, attitude
// within 5 deg and lateral error within 2 cm after settling (the last 5 s), no foot
// sliding more than 1 cm per stance. NOT MET YET: the spring stance is unstable in
// roll/lateral (period-2 growth ~3x per stride; see docs/full_model.md, "Limits (open)"), so the
// run falls at t ~ 1.7 s. Marked [!mayfail] so it reports without failing the suite.
// Issue 4's running criterion: from 10 deg roll and 0.2 m lateral offset the robot
// runs after a setpoint moving at 0.3 m/s for 10 s; over the last 5 s attitude within
// 5 deg, lateral error within 2 cm, no foot sliding more than 1 cm per stance. The
// scene levels the feet for each touchdown (level_feet) and holds roll and pitch in
// stance (stance_attitude). Measured: tilt <= 0.57 deg and lateral error <= 4.5 mm
// over the last 5 s (0.2 -> 0.016 m by t = 5 s), slip <= 2.4 mm, energy balance
// 4.2e-6 of the scale, 46 strides, ~33 s wall.
TEST_CASE("robot runs after a moving setpoint in the full model (pr_running)", "[robot][heavy]") {
  const scene::Scene s = load("pr_running.json");
  REQUIRE(s.simulation.duration >= 10.0);
  const robot::RobotRunResult r = robot::simulate(s);
  REQUIRE(r.run.status == reduced::RunStatus::kCompleted);
  double max_tilt = 0.0, max_lateral = 0.0;
  for (const auto& smp : r.run.trajectory) {
    if (smp.t < 5.0) continue;
    max_tilt = std::max({max_tilt, std::abs(smp.euler123.x()), std::abs(smp.euler123.y())});
    max_lateral = std::max(max_lateral, std::abs(smp.position.y() - smp.setpoint.y()));
  }
  CHECK(max_tilt <= 5.0 * kDeg);
  CHECK(max_lateral <= 0.02);
  for (double slip : r.stride_slip) CHECK(slip <= 0.01);
  CHECK(r.monitors.max_slip <= 0.01);
  CHECK(r.monitors.energy_drift <= 1e-3 * r.monitors.energy_scale);
}

// Stance attitude feedback (pseudo_rigid.stance_attitude) against the period-2 roll
// mode of the running robot. Reference: the same scene without the feedback, started
// level 5 cm off the setpoint, where the touchdown roll grows from ~0.2 deg to ~7 deg
// within 3 s (measured: 0.19, -0.2, 0.04, 0.22, -0.73, 1.29, -2.86, 7.04 deg ...).
// With kd = [10, 1] N m s/rad the touchdown roll stays below 0.3 deg (measured).
TEST_CASE("stance attitude feedback removes the running robot's period-2 roll mode",
          "[robot][heavy]") {
  // (The scene's own level feet and stance gains are replaced: open loop is no feedback.)
  const std::vector<std::string> level = {
      "/initial/position=[0,0.05,0.4]", "/initial/attitude_deg=[0,0,0]", "/simulation/duration=3",
      "/pseudo_rigid/level_feet=false", "/pseudo_rigid/stance_attitude={}"};
  auto max_roll = [](const robot::RobotRunResult& r) {
    double m = 0.0;
    for (const auto& st : r.run.strides) m = std::max(m, std::abs(st.euler123.x()));
    return m;
  };
  const robot::RobotRunResult open = robot::simulate(load("pr_running.json", level), {false});
  std::vector<std::string> fb(level.begin(), level.end() - 1);
  fb.push_back("/pseudo_rigid/stance_attitude={\"kd\":[10,1]}");
  const robot::RobotRunResult closed = robot::simulate(load("pr_running.json", fb), {false});
  REQUIRE(closed.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(closed.run.strides.size() >= 10);
  CHECK(max_roll(open) > 2.0 * kDeg);  // the mode is there without the feedback
  CHECK(max_roll(closed) < 0.5 * kDeg);
  for (double slip : closed.stride_slip) CHECK(slip <= 0.01);
  CHECK(closed.monitors.energy_drift <= 1e-3 * closed.monitors.energy_scale);
}

// Level feet (pseudo_rigid.level_feet) against the criterion's 10 deg roll start.
// Reference: the same scene without them, where the low side's feet land first and
// the body pivots on them (measured: first-stance lateral impulse +0.97 N s for
// -0.12 asked, roll 10.4 -> -22.5 deg by the next touchdown, tilted past 60 deg at
// t = 1.25 s). With them all four feet land together and the stance feedback levels
// the body in the first stance (measured: roll -1.50 deg at the second touchdown,
// first-stance lateral impulse +0.11 N s, roll within 0.6 deg from the third touchdown on).
// On RODAS4 at rtol 1e-6, atol 1e-8, as measured: the open-loop landing is chaotic (Verlet at
// h = 1.2e-4 s, auto's choice, lands the third stride at -1.1 deg instead of +2.1 deg and does
// not fall by 1.5 s; docs/solvers.md, "Limits").
TEST_CASE("level feet let the running robot recover from a 10 deg roll landing", "[robot][heavy]") {
  // (the four-mass body these bars were measured on)
  const std::vector<std::string> shortened = {"/simulation/duration=1.5",
                                              R"(/pseudo_rigid/solver={"method":"rodas4"})",
                                              "/pseudo_rigid/body=\"four_masses\""};
  std::vector<std::string> off = shortened;
  off.push_back("/pseudo_rigid/level_feet=false");
  const robot::RobotRunResult open = robot::simulate(load("pr_running.json", off), {false});
  const robot::RobotRunResult level = robot::simulate(load("pr_running.json", shortened), {false});
  CHECK(open.run.status == reduced::RunStatus::kFell);
  REQUIRE(open.run.strides.size() >= 2);
  CHECK(std::abs(open.run.strides[1].euler123.x()) > 15.0 * kDeg);
  REQUIRE(level.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(level.run.strides.size() >= 5);
  CHECK(std::abs(level.run.strides[1].euler123.x()) < 2.5 * kDeg);
  CHECK(std::abs(level.run.strides[0].P_delivered.y()) < 0.3);
  // Roll at the later touchdowns: at most 1.2 deg measured (under 1 deg while a foot's tap on the
  // tilted landing still set the next stance time; the open robot is past 15 deg at stride 1).
  for (size_t k = 2; k < level.run.strides.size(); ++k) {
    CHECK(std::abs(level.run.strides[k].euler123.x()) < 1.5 * kDeg);
  }
  CHECK(level.monitors.max_slip <= 0.01);
  CHECK(level.monitors.energy_drift <= 1e-3 * level.monitors.energy_scale);
}

TEST_CASE("robot: the full model refuses zero gravity before it builds or runs", "[robot]") {
  // It used to start and end "non-finite state at t = 0 s" (the leg placement's flight
  // time sqrt(2 dz / g)), then fail writing a non-finite energy figure.
  for (const char* body : {"four_masses", "rigid"}) {
    INFO(body);
    scene::Scene s = load("pr_running.json", {std::string("/pseudo_rigid/body=\"") + body + "\""});
    s.gravity = 0.0;
    const std::string why =
        "gravity 0 m/s^2: the full model needs gravity > 0 (its legs are placed for the "
        "touchdown a ballistic flight reaches; without gravity no flight ends)";
    CHECK_THROWS_WITH(robot::build_robot(s), why);
    CHECK_THROWS_WITH(robot::simulate(s), why);
    s.gravity = -9.81;  // out of the loader's range; made in code, refused the same way
    CHECK_THROWS_WITH(robot::simulate(s), Catch::Matchers::StartsWith("gravity -9.81 m/s^2"));
  }
}
