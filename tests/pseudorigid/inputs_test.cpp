// A run's MechanismInputs (inputs.hpp) against the same changes made to a copy of the
// Mechanism: leg rest lengths, a slide turned, a slide become a bilateral plane (a slot), a
// slide that holds no node. Every quantity the system computes is the same bit for bit, on
// the running robot's mechanism with its four-mass body and with its rigid body.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/inputs.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"

using namespace pronk;
using namespace pronk::pseudorigid;

namespace {

/// The robot's state perturbed off rest: every position and momentum moved a little, feet
/// 1 mm into the ground and sliding, so that springs, dampers, slides and friction all act.
ode::Vec moving_state(const robot::RobotModel& r) {
  ode::Vec y = r.mechanism.initial_state();
  for (size_t j = 0; j < r.mechanism.masses.size(); ++j) {
    const double s = static_cast<double>(j) + 1.0;
    y.segment<3>(6 * j) += 1e-3 * Eigen::Vector3d(std::sin(s), std::cos(2 * s), std::sin(3 * s));
    y.segment<3>(6 * j + 3) +=
        r.mechanism.masses[j].mass * Eigen::Vector3d(0.1 * std::cos(s), 0.2 * std::sin(s), -0.3);
  }
  for (int f : r.foot) y[6 * f + 2] = -1e-3;
  return y;
}

/// pr_running's robot with the given body (a JSON string) and dampers on the legs and the
/// ground contact, so that every kind of force acts.
robot::RobotModel damped_robot(const char* body) {
  return robot::build_robot(
      io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json",
                     {std::string("/pseudo_rigid/body=") + body, "/pseudo_rigid/leg_damping=2",
                      "/pseudo_rigid/contact_damping=5"}));
}

/// What a run changes, made both in inputs and in the copy of the mechanism.
void change(const robot::RobotModel& r, MechanismInputs& in, Mechanism& copy) {
  for (int c : r.leg_spring) {
    in.rest_length[c] *= 1.1;
    copy.connections[c].rest_length = in.rest_length[c];
  }
  const Eigen::Vector3d turned = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  in.surfaces[r.slide[0]].direction = turned;
  copy.surfaces[r.slide[0]].direction = turned;
  const Eigen::Vector3d slot = Eigen::Vector3d(0.0, 1.0, 0.1).normalized();
  SurfaceInputs& s1 = in.surfaces[r.slide[1]];
  s1.type = SurfaceType::kPlane;
  s1.bilateral = true;
  s1.direction = slot;
  Surface& c1 = copy.surfaces[r.slide[1]];
  c1.type = SurfaceType::kPlane;
  c1.bilateral = true;
  c1.direction = slot;
  in.surfaces[r.slide[2]].holds = false;
  copy.surfaces[r.slide[2]].nodes.clear();
}

/// a and b agree on everything at y; y1: the end of a step from y (correct_step).
void check_same(const MechanismSystem& a, const MechanismSystem& b, const ode::Vec& y,
                const ode::Vec& y1) {
  const int n = a.dimension();
  ode::Vec fa(n), fb(n);
  a.rhs(0.0, y, fa);
  b.rhs(0.0, y, fb);
  CHECK(fa == fb);
  a.conservative_rhs(0.0, y, fa);
  b.conservative_rhs(0.0, y, fb);
  CHECK(fa == fb);
  Eigen::SparseMatrix<double> ja, jb;
  a.jacobian(0.0, y, ja);
  b.jacobian(0.0, y, jb);
  CHECK(Eigen::MatrixXd(ja) == Eigen::MatrixXd(jb));
  const Energies ea = a.energies(y), eb = b.energies(y);
  CHECK(ea.total() == eb.total());
  CHECK(ea.leg == eb.leg);
  CHECK(ea.contact == eb.contact);
  const StateMonitors ma = a.monitors(y), mb = b.monitors(y);
  CHECK(ma.max_strain == mb.max_strain);
  CHECK(ma.max_penetration == mb.max_penetration);
  CHECK(a.power(y).dissipated == b.power(y).dissipated);
  CHECK(a.surface_forces(y) == b.surface_forces(y));
  ode::Vec da = y, db = y;
  CHECK(a.dissipate(0.0, 1e-4, y, da) == b.dissipate(0.0, 1e-4, y, db));
  CHECK(da == db);
  ode::Vec ca = y1, cb = y1;
  a.correct_step(y, ca);
  b.correct_step(y, cb);
  CHECK(ca == cb);
}

}  // namespace

TEST_CASE("mechanism inputs act as the same change to the mechanism, bit for bit",
          "[pseudorigid]") {
  for (const char* body : {"\"four_masses\"", "\"rigid\""}) {
    INFO("body " << body);
    const robot::RobotModel r = damped_robot(body);
    REQUIRE(r.slide.size() >= 3);
    const ode::Vec y = moving_state(r);
    ode::Vec y1 = y;  // foot 0 leaves the ground during the step
    y1[6 * r.foot[0] + 2] = 1e-3;
    // Unchanged inputs: the system with its own inputs and with the run's agree.
    const MechanismInputs same(r.mechanism);
    check_same(MechanismSystem(r.mechanism), MechanismSystem(r.mechanism, same), y, y1);
    // Changed inputs against the changed copy.
    MechanismInputs in(r.mechanism);
    Mechanism copy = r.mechanism;
    change(r, in, copy);
    const MechanismSystem with_inputs(r.mechanism, in), with_copy(copy);
    check_same(with_inputs, with_copy, y, y1);
    // And the change matters: the unchanged system differs.
    ode::Vec f0(y.size()), f1(y.size());
    MechanismSystem(r.mechanism).rhs(0.0, y, f0);
    with_inputs.rhs(0.0, y, f1);
    CHECK_FALSE(f0 == f1);
  }
}

// observe() (energies, monitors, surface forces) reads the positions' part of the last
// conservative evaluation (split Verlet's one RHS per step) when it is at the same positions
// and surface inputs: the same numbers as a system that never evaluated, bit for bit; after the
// inputs or a position change it computes them afresh.
TEST_CASE("observe reads the conservative evaluation at the same positions, bit for bit",
          "[pseudorigid]") {
  for (const char* body : {"\"four_masses\"", "\"rigid\""}) {
    INFO("body " << body);
    const robot::RobotModel r = damped_robot(body);
    const ode::Vec y = moving_state(r);
    MechanismInputs in(r.mechanism);
    const MechanismSystem warm(r.mechanism, in), cold(r.mechanism, in);
    auto same = [&](const ode::Vec& at) {
      const Energies ew = warm.energies(at), ec = cold.energies(at);
      CHECK(ew.total() == ec.total());
      CHECK(ew.internal == ec.internal);
      CHECK(ew.leg == ec.leg);
      CHECK(ew.contact == ec.contact);
      CHECK(warm.surface_forces(at) == cold.surface_forces(at));
      return ew.contact;
    };
    ode::Vec f(y.size());
    warm.conservative_rhs(0.0, y, f);
    // The step's closing kick changes the momenta only: the memo holds.
    ode::Vec y1 = y;
    for (size_t j = 0; j < r.mechanism.masses.size(); ++j) y1.segment<3>(6 * j + 3) *= 0.5;
    const double contact = same(y1);
    CHECK(warm.memo_hits() == 2);  // energies and surface forces
    CHECK(cold.memo_hits() == 0);
    CHECK(contact > 0.0);  // the slides and the feet in the ground count
    // A slide turned after the evaluation: computed afresh, and it matters.
    in.surfaces[r.slide[0]].direction = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
    CHECK(same(y1) != contact);
    CHECK(warm.memo_hits() == 2);
    // A position moved after a new evaluation: computed afresh.
    warm.conservative_rhs(0.0, y1, f);
    ode::Vec y2 = y1;
    y2[6 * r.foot[0] + 2] -= 1e-4;
    same(y2);
    CHECK(warm.memo_hits() == 2);
    same(y1);
    CHECK(warm.memo_hits() == 4);
  }
}

TEST_CASE("mechanism inputs must be sized to the mechanism", "[pseudorigid]") {
  const scene::Scene s =
      io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json");
  const robot::RobotModel r = robot::build_robot(s);
  MechanismInputs in(r.mechanism);
  in.surfaces.pop_back();
  CHECK_THROWS_AS(MechanismSystem(r.mechanism, in), std::invalid_argument);
}
