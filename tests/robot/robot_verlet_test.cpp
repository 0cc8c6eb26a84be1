// The robot in the full model on velocity Verlet (issue 18): the robot system forwards
// the mechanism's dissipation split (foot friction, dampers) so Verlet runs the regularised
// friction implicitly; against a tight RODAS4 reference of the same scene; the energy
// balance at every sample within the energy budget; the settings; and a step past
// Verlet's stability limit ends the run `diverged` with its numbers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "sim/io/robot_settings.hpp"
#include "sim/io/scene_loader.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/robot/robot_system.hpp"

using namespace pronk;

namespace {

constexpr double kDeg = M_PI / 180.0;

scene::Scene load(const std::string& name, const std::vector<std::string>& set = {}) {
  return io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + name, set);
}

/// The largest |balance(t) - balance(0)| over the samples [J].
double worst_sample(const robot::RobotRunResult& r) {
  auto balance = [](const robot::RobotSample& s) {
    return s.energies.total() + s.dissipated - s.actuator_work;
  };
  double worst = 0.0;
  for (const auto& s : r.samples) {
    worst = std::max(worst, std::abs(balance(s) - balance(r.samples.front())));
  }
  return worst;
}

/// Tilt of the body z axis from the vertical [rad] from Euler 123 angles.
double tilt(const Eigen::Vector3d& e) { return std::acos(std::cos(e.x()) * std::cos(e.y())); }

}  // namespace

TEST_CASE("robot system forwards the mechanism's dissipation split and metric", "[robot]") {
  const scene::Scene s = load("pr_running.json");
  const robot::RobotModel model = robot::build_robot(s);
  robot::RobotSystem sys(model, model.mechanism, s.pseudo_rigid);
  REQUIRE(sys.has_dissipation_split());
  CHECK(sys.momentum_block() == 3);
  const int n = sys.dimension();
  // A state with foot 0 pressed 1 mm into the ground and sliding at 0.2 m/s, its leg
  // compressing: friction, contact and leg dampers all act on it.
  ode::Vec y = model.mechanism.initial_state();
  const int f = model.foot[0];
  y[6 * f + 2] = -1e-3;
  y.segment<3>(6 * f + 3) = s.pseudo_rigid.foot_mass * Eigen::Vector3d(0.2, -0.1, -0.3);
  double kinetic = 0.0;
  for (size_t j = 0; j < model.mechanism.masses.size(); ++j) {
    kinetic += y.segment<3>(6 * j + 3).squaredNorm() / (2.0 * model.mechanism.masses[j].mass);
  }
  CHECK(sys.kinetic_energy(y) == Approx(kinetic).epsilon(1e-14));
  // The dissipative forces are rhs - conservative_rhs; dissipate() applies them implicitly,
  // so over a short h the momentum change is h times them (backward Euler, error O(h^2)).
  ode::Vec full(n), cons(n);
  sys.rhs(0.0, y, full);
  sys.conservative_rhs(0.0, y, cons);
  const ode::Vec fd = full - cons;
  REQUIRE(fd.segment<2>(6 * f + 3).norm() > 1.0);  // friction ~ mu N acts
  for (double h : {1e-9, 1e-10}) {
    ode::Vec yd = y;
    const double dissipated = sys.dissipate(0.0, h, y, yd);
    CHECK(dissipated > 0.0);
    const ode::Vec rate = (yd - y) / h;
    CHECK((rate - fd).norm() <= 1e-3 * fd.norm());
  }
  // Off the ground nothing is split off but the leg damper.
  ode::Vec y_air = model.mechanism.initial_state();
  sys.rhs(0.0, y_air, full);
  sys.conservative_rhs(0.0, y_air, cons);
  CHECK((full - cons).norm() < 1e-12);  // at rest relative to the body: no damping
}

TEST_CASE("robot pseudo_rigid solver energy_tol: read, validated, written back, listed unused",
          "[robot]") {
  const scene::Scene v = load("pr_running.json", {"/pseudo_rigid/solver/method=\"verlet\"",
                                                  "/pseudo_rigid/solver/energy_tol=2e-4"});
  CHECK(v.pseudo_rigid.energy_tol == 2e-4);
  const nlohmann::json back = io::scene_to_json(v);
  CHECK(back["pseudo_rigid"]["solver"]["energy_tol"] == 2e-4);
  CHECK(io::scene_to_json(io::parse_scene(back, "resolved")) == back);
  auto unused = [](const scene::Scene& s) {
    const auto u = io::unused_settings(s);
    return std::find(u.begin(), u.end(), "/pseudo_rigid/solver/energy_tol") != u.end();
  };
  CHECK_FALSE(unused(v));
  CHECK(unused(load("pr_running.json", {"/pseudo_rigid/solver/method=\"rodas4\""})));
  for (const char* bad : {"-1e-4", "0.9", "\"tight\""}) {
    try {
      load("pr_running.json", {std::string("/pseudo_rigid/solver/energy_tol=") + bad});
      FAIL("energy_tol " << bad << " accepted");
    } catch (const io::InputError& e) {
      CHECK(std::string(e.what()).find("/pseudo_rigid/solver/energy_tol") != std::string::npos);
    }
  }
}

// Verlet past its stability limit (h = 1 ms, where the 1 g feet on 1e5 N/m slides ring at
// ~1.4e4 rad/s, omega h ~ 14), and stiffness the step cannot resolve (contact 1e8 N/m at
// 1e-4 s): each run ends `diverged`, with the time, the step and the stability bound in the
// reason, and never hands back a non-finite number.
TEST_CASE("robot on verlet past its stability limit ends diverged with numbers, never NaN",
          "[robot]") {
  const std::vector<std::vector<std::string>> cases = {
      {"/pseudo_rigid/solver/h_fixed=1e-3"},
      {"/pseudo_rigid/solver/h_fixed=1e-4", "/pseudo_rigid/contact_stiffness=1e8"}};
  for (const auto& extra : cases) {
    std::vector<std::string> set = {"/pseudo_rigid/solver/method=\"verlet\"",
                                    "/pseudo_rigid/solver/energy_tol=0", "/simulation/duration=2"};
    set.insert(set.end(), extra.begin(), extra.end());
    const robot::RobotRunResult r = robot::simulate(load("pr_running.json", set));
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
