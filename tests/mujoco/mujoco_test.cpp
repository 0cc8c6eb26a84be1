// "model": "mujoco": the leg joints' kinematics against finite differences, the MJCF model's
// mass properties against the scene, the running robot in MuJoCo against the pseudo-rigid full
// model stride by stride, a MuJoCo run past its stability limit ending `diverged` with MuJoCo's
// warning named, and the loader's refusals (a build without MuJoCo refuses the model itself).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include <Eigen/Eigenvalues>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/mujoco/leg_joints.hpp"
#include "sim/mujoco/robot_mjcf.hpp"
#include "sim/robot/fidelity.hpp"
#include "sim/simulate.hpp"
#include "tests/support/scenes.hpp"

#ifdef PRONK_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

using namespace pronk;
using Eigen::Vector3d;

namespace {

io::InputError error_of(const std::string& name, const std::vector<std::string>& set) {
  try {
    (void)test::load_shipped(name, set);
  } catch (const io::InputError& e) {
    return e;
  }
  FAIL("no InputError");
  return io::InputError("", "", "", "");
}

}  // namespace

TEST_CASE("leg joints: the foot's rate is the joints' rates through the kinematics", "[mujoco]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double length = 0.25, h = 1e-6;
  for (int trial = 0; trial < 50; ++trial) {
    // A foot below its hip within 60 deg of the vertical, moving any way.
    const Vector3d d = Vector3d(0.5 * u(rng), 0.5 * u(rng), -1.0).normalized();
    const Vector3d r = (0.2 + 0.1 * (u(rng) + 1.0)) * d;
    const Vector3d r_rate(u(rng), u(rng), u(rng));
    const mujoco::LegJoints q = mujoco::leg_joints(r, r_rate, length);
    Vector3d r_back, rate_back;
    mujoco::foot_offset(q, length, &r_back, &rate_back);
    CHECK((r_back - r).norm() < 1e-14);
    CHECK((rate_back - r_rate).norm() < 1e-13);
    // Central differences of the position along the joint rates (an independent check of the
    // partial derivatives both directions use).
    auto at = [&](double s) {
      mujoco::LegJoints p = q;
      p.roll += s * q.roll_rate;
      p.pitch += s * q.pitch_rate;
      p.slide += s * q.slide_rate;
      Vector3d x, v;
      mujoco::foot_offset(p, length, &x, &v);
      return x;
    };
    const Vector3d fd = (at(h) - at(-h)) / (2.0 * h);
    CHECK((fd - r_rate).norm() < 1e-7 * (1.0 + r_rate.norm()));
  }
}

TEST_CASE("mujoco: a scene of another fidelity or a step too long is refused with its pointer",
          "[mujoco]") {
  if (!scene::mujoco_available()) {
    const io::InputError e = error_of("pr_running", {"/model=\"mujoco\""});
    CHECK(e.pointer() == "/model");
    CHECK_THAT(e.expected(), Catch::Matchers::Contains("built without MuJoCo"));
    return;
  }
  CHECK(error_of("pr_running", {"/model=\"mujoco\"", "/mujoco/timestep=0.05"}).pointer() ==
        "/mujoco/timestep");
  CHECK(error_of("pr_running", {"/model=\"mujoco\"", "/mujoco/step=0.001"}).pointer() ==
        "/mujoco/step");
  CHECK(error_of("pr_running", {"/model=\"mujoco\"", "/pseudo_rigid/legs=\"force\""}).pointer() ==
        "/pseudo_rigid/legs");
  // (MuJoCo's feet are bodies: massless feet are the full model's alone)
  CHECK(error_of("pr_running", {"/model=\"mujoco\"", "/pseudo_rigid/feet=\"quasi_static\""})
            .pointer() == "/pseudo_rigid/feet");
}

#ifdef PRONK_HAVE_MUJOCO

TEST_CASE("mujoco: the MJCF robot has the scene's mass, inertia and legs", "[mujoco]") {
  const scene::Scene s = test::load_shipped("pr_running", {"/model=\"mujoco\""});
  scene::Scene rigid = s;
  rigid.pseudo_rigid.body = scene::PseudoRigid::BodyKind::kRigid;
  const robot::RobotModel model = robot::build_robot(rigid);
  const std::string xml = mujoco::robot_mjcf(rigid, model);
  char error[1000] = "";
  mjVFS* vfs = new mjVFS;
  mj_defaultVFS(vfs);
  REQUIRE(mj_makeEmptyFileVFS(vfs, "r.xml", static_cast<int>(xml.size())) == 0);
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs, "r.xml")], xml.data(), xml.size());
  mjModel* m = mj_loadXML("r.xml", vfs, error, sizeof error);
  mj_deleteVFS(vfs);
  delete vfs;
  INFO(error);
  REQUIRE(m != nullptr);
  double mass = 0.0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  CHECK(mass == Approx(s.body.mass + 4 * s.pseudo_rigid.foot_mass).epsilon(1e-12));
  const int body = mj_name2id(m, mjOBJ_BODY, "body");
  // MuJoCo diagonalises the inertia (its principal axes in body_iquat, moments in its own
  // order): the same principal moments as the scene's tensor.
  std::vector<double> mj(m->body_inertia + 3 * body, m->body_inertia + 3 * body + 3);
  const Eigen::Vector3d ev =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(s.body.inertia).eigenvalues();
  std::vector<double> scene_moments(ev.data(), ev.data() + 3);
  std::sort(mj.begin(), mj.end());
  std::sort(scene_moments.begin(), scene_moments.end());
  for (int k = 0; k < 3; ++k) CHECK(mj[k] == Approx(scene_moments[k]).epsilon(1e-9));
  CHECK(m->nu == 4);
  CHECK(m->neq == 8);
  CHECK(m->nq == 7 + 4 * 3);
  CHECK(m->opt.timestep == s.mujoco.timestep);
  mj_deleteModel(m);
}

TEST_CASE("mujoco: refining MuJoCo's step moves pr_running's strides towards the full model",
          "[mujoco]") {
  // The reference: the full model (rigid body), converged to 0.13 % in apex (docs/mujoco.md).
  scene::Scene full = test::load_shipped("pr_running", {"/pseudo_rigid/body=\"rigid\""});
  full.simulation.duration = 3.0;
  RunOptions o;
  o.record_trajectory = false;
  const RunResult ref = simulate(full, o);
  REQUIRE(ref.run.status == reduced::RunStatus::kCompleted);
  auto in_mujoco = [&](double timestep) {
    scene::Scene mj = test::load_shipped("pr_running", {"/model=\"mujoco\""});
    mj.simulation.duration = 3.0;
    mj.mujoco.timestep = timestep;
    const RunResult r = simulate(mj, o);
    CHECK(r.run.status == reduced::RunStatus::kCompleted);
    CHECK_FALSE(r.mjcf.empty());
    CHECK_FALSE(r.monitors.energy_measured);
    return robot::compare_strides(r.run, ref.run, 10);
  };
  const robot::FidelityDiscrepancy coarse = in_mujoco(5e-4), fine = in_mujoco(1.25e-4);
  REQUIRE(coarse.strides == 10);
  REQUIRE(fine.strides == 10);
  // MuJoCo's contact stiffens towards the scene's as its step shrinks (1 / (2 timestep)):
  // apex and stance time move towards the full model's (measured 2.2 -> 1.0 %, 6.1 -> 3.4 %).
  CHECK(fine.max_apex_relative < coarse.max_apex_relative);
  CHECK(fine.max_stance_relative < coarse.max_stance_relative);
  CHECK(fine.max_apex_relative < 0.015);
  CHECK(fine.max_stance_relative < 0.05);
}

TEST_CASE("mujoco: a leg spring MuJoCo cannot step ends diverged with MuJoCo's warning",
          "[mujoco][extremes]") {
  // A 1e9 N/m leg spring on a 1 g foot (omega 1e6 rad/s) at MuJoCo's 1 ms explicit spring.
  scene::Scene s =
      test::load_shipped("pr_running", {"/model=\"mujoco\"", "/pseudo_rigid/leg_stiffness=1e9"});
  s.simulation.duration = 1.0;
  s.mujoco.timestep = 1e-3;
  const RunResult r = simulate(s);
  CHECK(r.run.status == reduced::RunStatus::kDiverged);
  CHECK_THAT(r.run.reason, Catch::Matchers::Contains("MuJoCo Euler, step 0.001 s"));
  CHECK_THAT(r.run.reason, Catch::Matchers::Contains("mjWARN_BAD"));
  CHECK(r.run.final_position.allFinite());
  for (const auto& p : r.run.trajectory) CHECK(p.position.allFinite());
}

#endif
