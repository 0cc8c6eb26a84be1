// The rigid-body rung of the full model ("pseudo_rigid": {"body": "rigid"}): a torque-free
// rigid body conserves energy, angular momentum and |q| = 1 and turns as the four-mass body
// does; the robot with a rigid body agrees stride by stride with the four-mass body at internal
// stiffness 1e7 N/m; the settings a rigid body ignores are listed unused; and a step past
// Verlet's stability limit ends `diverged` with its numbers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/attitude.hpp"
#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/robot/fidelity.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/simulate.hpp"

using namespace pronk;
namespace pr = pronk::pseudorigid;

namespace {

constexpr double kRbDeg = M_PI / 180.0;

scene::Scene rb_load(const std::string& name, const std::vector<std::string>& set = {}) {
  return io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + name, set);
}

/// A free body in zero gravity: 1.5 kg, a full (non-diagonal) inertia tensor, spinning about
/// a generic axis near its middle principal axis (the unstable one: the motion tumbles).
pr::Mechanism rb_free_body(bool rigid, ode::Method method) {
  pr::Mechanism m;
  m.gravity.setZero();
  pr::BodySpec b;
  b.mass = 1.5;
  b.inertia << 0.0074, 0.001, -0.0005, 0.001, 0.0106, 0.0008, -0.0005, 0.0008, 0.0164;
  b.com = Eigen::Vector3d(0.1, -0.2, 0.3);
  b.velocity = Eigen::Vector3d(0.3, 0.1, -0.2);
  b.attitude = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  b.omega = Eigen::Vector3d(0.3, 4.0, 0.5);
  b.internal_stiffness = 1e7;
  b.rigid = rigid;
  std::string err;
  REQUIRE(pr::add_body(m, b, &err) == 0);
  m.simulation.t_end = 2.0;
  m.simulation.output_interval = 0.01;
  m.simulation.solver.method = method;
  if (method == ode::Method::kVerlet) {
    m.simulation.solver.h_fixed = 1e-3;
  } else {
    m.simulation.solver.rtol = 1e-10;
    m.simulation.solver.atol = 1e-12;
  }
  return m;
}

/// Body-to-world rotation of body 0 at state y.
Eigen::Matrix3d rb_rotation(const pr::Mechanism& m, const ode::Vec& y) {
  const pr::MechanismSystem sys(m);
  return sys.frames(y)[0].rotation;
}

}  // namespace

TEST_CASE("torque-free rigid body conserves energy, angular momentum and |q| = 1", "[rigid]") {
  // The four-mass body at 1e7 N/m (RODAS4, rtol 1e-10) is the independent reference of the
  // motion: its attitude after 2 s of tumbling within 2e-3 rad of the rigid body's.
  const pr::Mechanism ref = rb_free_body(false, ode::Method::kRodas4);
  const pr::RunSummary r = pr::simulate(ref);
  REQUIRE(r.status == pr::RunStatus::kCompleted);
  const Eigen::Matrix3d r_ref = rb_rotation(ref, r.y.back());
  for (ode::Method method : {ode::Method::kRodas4, ode::Method::kVerlet}) {
    const pr::Mechanism m = rb_free_body(true, method);
    REQUIRE(m.dimension() == 13);
    const pr::RunSummary s = pr::simulate(m);
    INFO(ode::to_string(method) << ": " << s.reason);
    REQUIRE(s.status == pr::RunStatus::kCompleted);
    const int q = m.rotation_state(0);
    const double e0 = s.energies.front().kinetic;
    double worst_e = 0.0, worst_l = 0.0, worst_q = 0.0;
    const Eigen::Vector3d l0 = s.y.front().segment<3>(q + 4);
    for (size_t k = 0; k < s.y.size(); ++k) {
      worst_e = std::max(worst_e, std::abs(s.energies[k].kinetic - e0) / e0);
      worst_l = std::max(worst_l, (s.y[k].segment<3>(q + 4) - l0).norm() / l0.norm());
      worst_q = std::max(worst_q, std::abs(s.y[k].segment<4>(q).norm() - 1.0));
    }
    // Kinetic energy 1/2 m v^2 + 1/2 omega . I omega from the initial state.
    const Eigen::Matrix3d r0 = m.bodies[0].attitude0.toRotationMatrix();
    const Eigen::Vector3d w0(0.3, 4.0, 0.5);  // (world)
    const Eigen::Matrix3d iw = r0 * m.bodies[0].inertia * r0.transpose();
    CHECK(e0 == Approx(0.5 * 1.5 * 0.14 + 0.5 * w0.dot(iw * w0)).epsilon(1e-12));
    CHECK(worst_l <= 1e-13);  // torque-free: L is never kicked
    CHECK(worst_q <= (method == ode::Method::kVerlet ? 1e-13 : 1e-8));
    // Verlet's energy error stays bounded at O((omega h)^2); RODAS4 at its tolerance.
    CHECK(worst_e <= (method == ode::Method::kVerlet ? 1e-4 : 1e-8));
    const Eigen::AngleAxisd diff(rb_rotation(m, s.y.back()) * r_ref.transpose());
    INFO("attitude vs four-mass: " << diff.angle() << " rad");
    CHECK(diff.angle() <= 2e-3);
    // The CoM moves at constant velocity.
    const Eigen::Vector3d x_end(0.1 + 0.3 * 2.0, -0.2 + 0.1 * 2.0, 0.3 - 0.2 * 2.0);
    CHECK((s.y.back().segment<3>(0) - x_end).norm() <= 1e-10);
  }
}

TEST_CASE("rigid body: scene setting, unused settings, refused dummy hips", "[rigid][robot]") {
  const scene::Scene s = rb_load("pr_running.json", {"/pseudo_rigid/body=\"rigid\""});
  CHECK(s.pseudo_rigid.body == scene::PseudoRigid::BodyKind::kRigid);
  const nlohmann::json back = io::scene_to_json(s);
  CHECK(back["pseudo_rigid"]["body"] == "rigid");
  CHECK(io::scene_to_json(io::parse_scene(back, "resolved")) == back);
  auto listed = [](const scene::Scene& sc, const std::string& p) {
    const auto u = io::unused_settings(sc);
    return std::find(u.begin(), u.end(), p) != u.end();
  };
  // Spring legs: internal_stiffness and internal_damping still hold the leg slides.
  CHECK(listed(s, "/pseudo_rigid/strain_budget"));
  CHECK(listed(s, "/pseudo_rigid/error_norm"));
  CHECK_FALSE(listed(s, "/pseudo_rigid/internal_stiffness"));
  CHECK_FALSE(listed(rb_load("pr_running.json", {"/pseudo_rigid/body=\"four_masses\""}),
                     "/pseudo_rigid/strain_budget"));
  // The default body is rigid (a scene that leaves it out: the family's tripod); with
  // dummy-mass hips, four masses. pr_running states the four masses it was recorded on.
  CHECK(rb_load("family/tripod.json").pseudo_rigid.body == scene::PseudoRigid::BodyKind::kRigid);
  CHECK(rb_load("family/tripod.json", {R"(/pseudo_rigid={"hips": "dummy_masses"})"})
            .pseudo_rigid.body == scene::PseudoRigid::BodyKind::kFourMasses);
  CHECK(rb_load("pr_running.json").pseudo_rigid.body == scene::PseudoRigid::BodyKind::kFourMasses);
  // Force legs: no slides, nothing of the body's springs is used.
  const scene::Scene f = rb_load("case5_pr_hop_height.json", {"/pseudo_rigid/body=\"rigid\""});
  for (const char* p : {"/pseudo_rigid/internal_stiffness", "/pseudo_rigid/internal_damping",
                        "/pseudo_rigid/strain_budget", "/pseudo_rigid/dummy_ratio"}) {
    INFO(p);
    CHECK(listed(f, p));
  }
  CHECK_FALSE(listed(rb_load("case5_pr_hop_height.json", {"/pseudo_rigid/body=\"four_masses\""}),
                     "/pseudo_rigid/internal_stiffness"));
  try {
    rb_load("pr_running.json",
            {"/pseudo_rigid/body=\"rigid\"", "/pseudo_rigid/hips=\"dummy_masses\""});
    FAIL("dummy hips accepted with a rigid body");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()).find("/pseudo_rigid/hips") != std::string::npos);
  }
  try {
    rb_load("pr_running.json", {"/pseudo_rigid/body=\"stiff\""});
    FAIL("body \"stiff\" accepted");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()).find("/pseudo_rigid/body") != std::string::npos);
  }
}

namespace {

/// Rigid vs four-mass body on one scene at an internal stiffness [N/m] (both: the slides too),
/// both on RODAS4 at rtol 1e-6, atol 1e-8, where the bars were measured: the comparison is of
/// the bodies, not of the solvers (auto's RODAS4 at 1e-5 moves pr_running's touchdown
/// attitudes by up to 0.2 deg at 1e7 N/m).
void rb_agree(const std::string& scene, const std::vector<std::string>& extra, size_t min_strides,
              double attitude_bar, double apex_bar = 1e-3, const char* stiffness = "1e7") {
  std::vector<std::string> set = {std::string("/pseudo_rigid/internal_stiffness=") + stiffness,
                                  R"(/pseudo_rigid/solver={"method":"rodas4"})"};
  set.insert(set.end(), extra.begin(), extra.end());
  set.push_back("/pseudo_rigid/body=\"four_masses\"");
  const robot::RobotRunResult four = robot::simulate(rb_load(scene, set));
  set.back() = "/pseudo_rigid/body=\"rigid\"";
  const robot::RobotRunResult rigid = robot::simulate(rb_load(scene, set));
  INFO(scene << ": four-mass " << four.run.reason << "; rigid " << rigid.run.reason);
  REQUIRE(four.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(rigid.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(four.run.strides.size() == rigid.run.strides.size());
  REQUIRE(four.run.strides.size() >= min_strides);
  const robot::FidelityDiscrepancy d = robot::compare_strides(four.run, rigid.run);
  INFO("apex " << d.max_apex << " m, touchdown attitude " << d.max_attitude / kRbDeg << " deg");
  CHECK(d.max_apex <= apex_bar);
  CHECK(d.max_attitude <= attitude_bar);
  CHECK(rigid.monitors.max_strain == 0.0);  // no internal springs
  CHECK(four.monitors.max_strain > 0.0);
  CHECK(rigid.monitors.energy_drift <= 1e-3 * rigid.monitors.energy_scale);
}

}  // namespace

TEST_CASE("rigid body agrees with the four-mass body stride by stride (case5 hop height)",
          "[rigid][robot]") {
  rb_agree("case5_pr_hop_height.json", {}, 6, 0.1 * kRbDeg);
}

// With force legs the rigid body IS the pulse model (a rigid body pushed by body-fixed constant
// forces at the hips for the pulse duration): an independent implementation (reduced
// simulator, body-rate Euler equations) of the same motion, to the solvers' tolerances.
TEST_CASE("rigid body with force legs reproduces the pulse model (case5 hop height)",
          "[rigid][robot]") {
  // (A tilted start, so the attitude control acts.)
  const scene::Scene s = rb_load("case5_pr_hop_height.json", {"/pseudo_rigid/body=\"rigid\"",
                                                              "/initial/attitude_deg=[4,-3,2]"});
  const robot::RobotRunResult rigid = robot::simulate(s);
  scene::Scene sp = s;
  sp.model = scene::ModelKind::kPulse;
  const RunResult pulse = simulate(sp);
  REQUIRE(rigid.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(pulse.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(rigid.run.strides.size() == pulse.run.strides.size());
  const robot::FidelityDiscrepancy d = robot::compare_strides(rigid.run, pulse.run);
  INFO("apex " << d.max_apex << " m, attitude " << d.max_attitude << " rad");
  CHECK(d.strides >= 8);
  CHECK(rigid.run.strides[1].euler123.norm() > 1e-3);  // the attitude moved
  CHECK(d.max_apex <= 1e-8);
  CHECK(d.max_attitude <= 1e-8);
  CHECK(d.max_touchdown_position <= 1e-8);
}

TEST_CASE("rigid body agrees with the four-mass body stride by stride (pr_running)",
          "[rigid][robot][heavy]") {
  // Measured: apexes within 2.4e-4 m, touchdown attitude within 0.162 deg over the 50 strides:
  // the 0.1 deg aimed at is not met at 1e7 N/m. The gap is the four-mass body's flexibility,
  // not an error of the rigid body: its flat tetrahedron (23 mm half-height) holds the
  // extrapolated hips at ~1e7 N/m laterally, so each foot is held at ~5e6 N/m (slide and hip in
  // series) against 1e7 on the rigid body; stride 1 differs by 0.04 deg, and with the slides at
  // 1e7 N/m the gait's period-2 roll/lateral mode grows on both bodies and amplifies that
  // (docs/pseudorigid.md, "Why pr_running's bodies differ"). The gap shrinks as the body
  // stiffens (next test). It is not the solver's: at rtol = atol = 1e-8 both runs move by at
  // most 1.2e-3 deg and the gap is 0.1621 deg. The bar is the measured value with margin.
  rb_agree("pr_running.json", {}, 40, 0.2 * kRbDeg);
}

TEST_CASE("the four-mass body converges to the rigid body as it stiffens (pr_running, 1e8 N/m)",
          "[rigid][robot][heavy]") {
  // Measured over 10 s (50 strides): 0.0195 deg and 3.1e-5 m at 1e8 N/m against 0.162 deg and
  // 2.4e-4 m at 1e7 (the solvers' share is below 1e-3 deg: RODAS4 at rtol 1e-9 moves the rigid
  // run's attitudes by less). 5 s here (25 strides), the bars with margin.
  rb_agree("pr_running.json", {"/simulation/duration=5"}, 20, 0.05 * kRbDeg, 1e-4, "1e8");
}

// Verlet past its stability limit with the rigid body (h = 1 ms: the 1 g feet on the 1e5 N/m
// slides ring at ~1.4e4 rad/s), and slides too stiff for the step (1e8 N/m at 1.5e-4 s): the run
// ends `diverged` with the time, the step and the stability bound, never a non-finite number.
TEST_CASE("rigid body on verlet past its stability limit ends diverged with numbers",
          "[rigid][robot]") {
  const std::vector<std::vector<std::string>> cases = {
      {R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1e-3})"},
      {R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-4})",
       "/pseudo_rigid/internal_stiffness=1e8"}};
  for (const auto& extra : cases) {
    std::vector<std::string> set = {"/simulation/duration=2", "/pseudo_rigid/body=\"rigid\""};
    set.insert(set.end(), extra.begin(), extra.end());
    const robot::RobotRunResult r = robot::simulate(rb_load("pr_running.json", set));
    INFO(extra.back() << ": " << r.run.reason);
    CHECK(r.run.status == reduced::RunStatus::kDiverged);
    CHECK(r.run.reason.find("verlet step") != std::string::npos);
    CHECK(r.run.reason.find("stable below h") != std::string::npos);
    CHECK(r.run.t_end < 2.0);
    CHECK(std::isfinite(r.monitors.energy_drift));
    CHECK(r.run.final_position.allFinite());
    for (const auto& smp : r.run.trajectory) REQUIRE(smp.position.allFinite());
    for (const auto& smp : r.samples) REQUIRE(std::isfinite(smp.energies.total()));
  }
}

// Verlet with the rigid body at a stable step (1.5e-4 s) over 3 s of pr_running: completes,
// keeps its energy balance at every sample within 1e-3 of the energy scale (the rotation's
// drift is the free rigid body's splitting flow, symplectic), and its strides agree with the
// rigid body on RODAS4 as well as the four-mass body's do.
TEST_CASE("rigid body on verlet keeps the energy balance and agrees with RODAS4",
          "[rigid][robot]") {
  const std::vector<std::string> base = {"/simulation/duration=3", "/pseudo_rigid/body=\"rigid\""};
  std::vector<std::string> v = base;
  v.push_back(R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-4})");
  const robot::RobotRunResult a = robot::simulate(rb_load("pr_running.json", v));
  const robot::RobotRunResult b = robot::simulate(rb_load("pr_running.json", base));
  INFO(a.run.reason << "; " << b.run.reason);
  REQUIRE(a.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(b.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(a.run.strides.size() == b.run.strides.size());
  double worst = 0.0;
  auto balance = [](const robot::RobotSample& s) {
    return s.energies.total() + s.dissipated - s.actuator_work;
  };
  for (const auto& s : a.samples) {
    worst = std::max(worst, std::abs(balance(s) - balance(a.samples.front())));
  }
  INFO("worst sample " << worst / a.monitors.energy_scale << " of the scale");
  CHECK(worst <= 1e-3 * a.monitors.energy_scale);
  const robot::FidelityDiscrepancy d = robot::compare_strides(a.run, b.run);
  INFO("apex " << d.max_apex << " m, attitude " << d.max_attitude / kRbDeg << " deg");
  // Near the four-mass body's Verlet vs RODAS4 (robot_verlet_test.cpp: apexes within 1 % over
  // 10 s): in this 3 s transient the rigid body's apexes differ by up to 4.3 mm (1.7 %, strides
  // 1-2; the four-mass body 1.1 mm), its touchdown attitude by 0.92 deg (four-mass: 1.29 deg).
  for (size_t k = 0; k < a.run.strides.size(); ++k) {
    const auto& sa = a.run.strides[k];
    const auto& sb = b.run.strides[k];
    if (!sa.has_apex || !sb.has_apex) continue;
    INFO("stride " << k << ": " << sa.apex_height << " vs " << sb.apex_height);
    CHECK(std::abs(sa.apex_height - sb.apex_height) <= 0.02 * sb.apex_height);
  }
  CHECK(d.max_attitude <= 1.5 * kRbDeg);
}

// The bench's rigid-body Verlet row (pr_running, 10 s, h = 1.5e-4 s with the energy budget
// energy_tol = 1e-5): every sample's balance within 1e-3 of the energy scale (without the
// budget the fixed step ends at 1.17e-3: the budget's refined sub-steps at the impacts bring it
// to 3.5e-4 for 0.6 % more steps).
TEST_CASE("rigid body on verlet with the energy budget keeps the balance over 10 s (pr_running)",
          "[rigid][robot]") {
  const robot::RobotRunResult r = robot::simulate(
      rb_load("pr_running.json",
              {"/pseudo_rigid/body=\"rigid\"",
               R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-4,"energy_tol":1e-5})"}));
  REQUIRE(r.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(r.run.t_end == 10.0);
  double worst = 0.0;
  auto balance = [](const robot::RobotSample& s) {
    return s.energies.total() + s.dissipated - s.actuator_work;
  };
  for (const auto& s : r.samples) {
    worst = std::max(worst, std::abs(balance(s) - balance(r.samples.front())));
  }
  INFO("worst sample " << worst / r.monitors.energy_scale << " of the scale");
  CHECK(worst <= 1e-3 * r.monitors.energy_scale);
  CHECK(r.monitors.energy_drift >= (1.0 - 1e-12) * worst);
}
