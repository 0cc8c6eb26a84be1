// Quasi-static (massless) feet (pseudo_rigid.feet "quasi_static", docs/notes/quasi_static_feet.md)
// against independent references: a standing robot's force balance computed by hand (springs
// in series), the creep law read off the ground reaction, the step bound's roll mode in closed
// form and the four-mass bound against the force law's differences (free and locked hips), the
// energy balance of a passive drop (a conservation law), and pr_running (free hips) and case 6
// (locked hips, frictionless) with 1 g feet stride by stride.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/robot/feet_step_bound.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/robot/robot_system.hpp"
#include "sim/robot/sampled_contacts.hpp"

using namespace pronk;
using Eigen::Vector3d;

namespace {

const std::string kQuasi = "/pseudo_rigid/feet=\"quasi_static\"";
const std::string kRigid = "/pseudo_rigid/body=\"rigid\"";

/// A shipped scene (studies/scenes/<name>.json) with `set` applied.
scene::Scene load_shipped(const std::string& name, const std::vector<std::string>& set) {
  std::string path = PRONK_SOURCE_DIR;  // (built with +=: GCC 12 warns falsely on "a" + b)
  path += "/studies/scenes/" + name + ".json";
  return io::load_scene(path, set);
}

scene::Scene load(const std::vector<std::string>& set) { return load_shipped("pr_running", set); }

/// The level body at CoM height z, at rest, every foot pinned on the ground under its hip.
ode::Vec standing(const robot::RobotModel& m, robot::RobotSystem& sys, double z) {
  ode::Vec y = sys.initial_state();
  const int c = 6 * m.mechanism.bodies[m.body].first_mass;
  y.segment<3>(c) = Vector3d(0.0, 0.0, z);
  y.segment<3>(c + 3).setZero();
  const int r = sys.rotation_state();
  y.segment<4>(r) << 1.0, 0.0, 0.0, 0.0;
  y.segment<3>(r + 4).setZero();
  for (size_t i = 0; i < m.hip.size(); ++i) {
    sys.land_foot(i, y);
    y.segment<2>(sys.foot_state(i)) = m.hip[i].head<2>();
  }
  return y;
}

}  // namespace

TEST_CASE("quasi-static feet: the setting is read, refused where it cannot act, listed",
          "[robot]") {
  const scene::Scene q = load({kRigid, kQuasi});
  CHECK(q.pseudo_rigid.feet == scene::PseudoRigid::Feet::kQuasiStatic);
  CHECK(load({kRigid}).pseudo_rigid.feet == scene::PseudoRigid::Feet::kMass);
  const auto u = io::unused_settings(q);
  for (const char* k : {"/pseudo_rigid/foot_mass", "/pseudo_rigid/contact_damping"}) {
    CHECK(std::find(u.begin(), u.end(), k) != u.end());
  }
  const auto u1 = io::unused_settings(load({kRigid}));
  CHECK(std::find(u1.begin(), u1.end(), "/pseudo_rigid/foot_mass") == u1.end());
  CHECK(std::find(u1.begin(), u1.end(), "/pseudo_rigid/feet") == u1.end());
  // Force legs have no feet: the setting is unused there (case 5).
  const auto u2 = io::unused_settings(load_shipped("case5_pr_hop_height", {kQuasi}));
  CHECK(std::find(u2.begin(), u2.end(), "/pseudo_rigid/feet") != u2.end());
  // Written back only when not the default (recorded scenes keep their hash); round-trips.
  CHECK(io::scene_to_json(q)["pseudo_rigid"]["feet"] == "quasi_static");
  CHECK_FALSE(io::scene_to_json(load({kRigid}))["pseudo_rigid"].contains("feet"));
  CHECK(io::scene_to_json(io::parse_scene(io::scene_to_json(q), "resolved")) ==
        io::scene_to_json(q));
  try {
    load({kRigid, "/pseudo_rigid/feet=\"massless\""});
    FAIL("accepted \"massless\"");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()).find("/pseudo_rigid/feet") != std::string::npos);
  }
  // Both bodies, free or locked stance hips; not on dummy hip masses (a hip off the body).
  CHECK(load({"/pseudo_rigid/body=\"four_masses\"", kQuasi}).pseudo_rigid.feet ==
        scene::PseudoRigid::Feet::kQuasiStatic);
  CHECK_THROWS_WITH(robot::build_robot(load({"/pseudo_rigid/body=\"four_masses\"", kQuasi,
                                             "/pseudo_rigid/hips=\"dummy\""})),
                    Catch::Contains("dummy"));
  CHECK(robot::build_robot(load({kRigid, kQuasi, "/pseudo_rigid/hip_rotation=false"}))
            .quasi_static_feet);
}

// A free hip's slot is the plane of the leg and the body x axis; a locked hip's is the leg's
// line: two normals across the leg, orthogonal to it and to each other.
TEST_CASE("quasi-static feet: the slot normals of free and locked hips", "[robot]") {
  for (const Vector3d& dir : {Vector3d(-Vector3d::UnitZ()), Vector3d(0.3, -0.2, -1.0).normalized(),
                              Vector3d(Vector3d::UnitX())}) {
    INFO(dir.transpose());
    const auto free = robot::slot_normals(dir, false);
    CHECK(free[1].norm() == 0.0);
    if (free[0].norm() > 0.0) {
      CHECK(free[0].norm() == Approx(1.0));
      CHECK(std::abs(free[0].dot(dir)) < 1e-12);
      CHECK(std::abs(free[0].x()) < 1e-12);  // the body x axis lies in the plane
    } else {
      CHECK(dir.cross(Vector3d::UnitX()).norm() < 1e-6);  // a leg along x has no slot
    }
    const auto locked = robot::slot_normals(dir, true);
    for (const Vector3d& n : locked) {
      CHECK(n.norm() == Approx(1.0));
      CHECK(std::abs(n.dot(dir)) < 1e-12);
    }
    CHECK(std::abs(locked[0].dot(locked[1])) < 1e-12);
  }
}

// Standing level with the legs vertical under the hips: each leg is its spring k in series
// with the ground spring k_c (the slots, horizontal, carry nothing), so it pushes
// F = k k_c / (k + k_c) (l0 - H), H the hip height; the body's rate of momentum is 4 F - M g
// and no torque; each ground reaction is F.
TEST_CASE("quasi-static feet: a standing robot's force balance, springs in series", "[robot]") {
  const scene::Scene s = load({kRigid, kQuasi, "/pseudo_rigid/stance_attitude/kp=[0,0]",
                               "/pseudo_rigid/stance_attitude/kd=[0,0]"});
  const robot::RobotModel m = robot::build_robot(s);
  REQUIRE(m.quasi_static_feet);
  const pseudorigid::MechanismInputs inputs(m.mechanism);
  robot::RobotSystem sys(m, inputs, s.pseudo_rigid);
  const double z = 0.24;
  ode::Vec y = standing(m, sys, z);
  ode::Vec f(sys.dimension());
  sys.rhs(0.0, y, f);
  const double k = s.pseudo_rigid.leg_stiffness, kc = s.pseudo_rigid.contact_stiffness;
  double total = 0.0;
  const std::vector<double> normal = sys.normal_forces(y);
  for (size_t i = 0; i < m.hip.size(); ++i) {
    const double H = z + m.hip[i].z();
    const double F = k * kc / (k + kc) * (m.rest_length[i] - H);
    CHECK(normal[i] == Approx(F).epsilon(1e-12));
    CHECK(sys.foot_position(i, y).z() == Approx(-F / kc).epsilon(1e-12));
    total += F;
  }
  const int c = 6 * m.mechanism.bodies[m.body].first_mass;
  CHECK(f[c + 5] == Approx(total - s.body.mass * s.gravity).epsilon(1e-12));
  CHECK(f.segment<2>(c + 3).norm() < 1e-12);
  CHECK(f.segment<3>(sys.rotation_state() + 4).norm() < 1e-12);
  CHECK(f.tail(2 * static_cast<int>(m.hip.size())).norm() < 1e-12);  // nothing slides
}

// One foot pushed sideways by its slot (the body shifted across the slots): over a short
// relaxation the foot slides at the creep law's speed v = v_s r / sqrt(1 - r^2) along the
// ground reaction's tangential push, r = |F_t| / (mu N), read off the reaction before it; the
// energy booked as released is the springs' loss, positive; rhs() gives the same rate.
TEST_CASE("quasi-static feet: a pinned foot creeps by the regularised friction law", "[robot]") {
  const scene::Scene s =
      load({kRigid, kQuasi, "/pseudo_rigid/stance_attitude/kp=[0,0]",
            "/pseudo_rigid/stance_attitude/kd=[0,0]", "/pseudo_rigid/friction=0.5"});
  const robot::RobotModel m = robot::build_robot(s);
  const pseudorigid::MechanismInputs inputs(m.mechanism);
  robot::RobotSystem sys(m, inputs, s.pseudo_rigid);
  ode::Vec y = standing(m, sys, 0.24);
  const int c = 6 * m.mechanism.bodies[m.body].first_mass;
  y[c + 1] = 1.6e-5;  // 16 um across the slots (their normal is the body y axis)
  const Vector3d g = sys.ground_reaction(0, y);
  const double mu_n = s.pseudo_rigid.friction * g.z();
  const Eigen::Vector2d push = -g.head<2>();
  const double r = push.norm() / mu_n;
  REQUIRE(r > 0.3);
  REQUIRE(r < 0.95);
  const Eigen::Vector2d v = s.pseudo_rigid.slip_velocity * push / (mu_n * std::sqrt(1 - r * r));
  ode::Vec f(sys.dimension());
  sys.rhs(0.0, y, f);
  CHECK((f.segment<2>(sys.foot_state(0)) - v).norm() < 1e-12 * v.norm() + 1e-15);
  const double h = 1e-7;
  ode::Vec y1 = y;
  bool moved = false;
  const double released = sys.relax(h, y1, &moved);
  CHECK(moved);
  const Eigen::Vector2d slid = (y1 - y).segment<2>(sys.foot_state(0)) / h;
  CHECK((slid - v).norm() < 1e-3 * v.norm());
  CHECK(released > 0.0);
  double lost = 0.0;
  for (size_t i = 0; i < m.hip.size(); ++i) lost += sys.foot_energy(i, y) - sys.foot_energy(i, y1);
  CHECK(released == Approx(lost).epsilon(1e-9));
  CHECK((y1 - y).head(sys.dimension() - 8).norm() == 0.0);  // the body does not move
}

// The bound's stiffest mode on level legs is the body's roll against its sideways shift on the
// slots: with n legs' slots k_s at the feet's depth z_f (their normal the body y axis) and their
// springs k at the hips' half-width w, the (y, roll) block K = n [[k_s, -k_s z_f],
// [-k_s z_f, k_s z_f^2 + k w^2]] over diag(M, I_xx) (the other modes decouple by symmetry).
TEST_CASE("quasi-static feet: the step bound's roll mode in closed form", "[robot]") {
  const scene::Scene s = load({kRigid, kQuasi});
  const robot::RobotModel m = robot::build_robot(s);
  const double ks = s.pseudo_rigid.internal_stiffness, k = s.pseudo_rigid.leg_stiffness;
  const double zf = m.hip[0].z() - m.rest_length[0], w = std::abs(m.hip[0].y());
  const double n = static_cast<double>(m.hip.size());
  const double a = n * ks / s.body.mass, d = n * (ks * zf * zf + k * w * w) / s.body.inertia(0, 0);
  const double b2 = n * n * ks * ks * zf * zf / (s.body.mass * s.body.inertia(0, 0));
  const double lambda = 0.5 * (a + d) + std::sqrt(0.25 * (a - d) * (a - d) + b2);
  const double omega = robot::quasi_static_omega(s, m, 1.0, -Vector3d::UnitZ());
  CHECK(omega == Approx(std::sqrt(lambda)).epsilon(1e-9));
  // The placement's range only raises it (longer and leaning legs).
  CHECK(robot::quasi_static_omega(s, m) >= omega);
}

// The four-mass body: the bound's 12 x 12 stiffness against central differences of the
// body's own force law (RobotSystem's conservative forces on its four masses, standing level
// on its feet at the rest length, every foot pinned under its hip), so that the bound auto
// steps at is the body's stiffest mode as the stepper sees it.
TEST_CASE("quasi-static feet: the four-mass body's step bound is its force law's stiffest mode",
          "[robot]") {
  // Free stance hips (one slot normal per foot) and locked ones (two).
  const std::string hips = GENERATE(std::string("/pseudo_rigid/hip_rotation=true"),
                                    std::string("/pseudo_rigid/hip_rotation=false"));
  INFO(hips);
  // (the stance feedback off: its moments are not a potential's)
  const scene::Scene s =
      load({"/pseudo_rigid/body=\"four_masses\"", kQuasi, "/pseudo_rigid/stance_attitude/kp=[0,0]",
            "/pseudo_rigid/stance_attitude/kd=[0,0]", hips});
  const robot::RobotModel m = robot::build_robot(s);
  REQUIRE(m.quasi_static_feet);
  const pseudorigid::MechanismInputs inputs(m.mechanism);
  robot::RobotSystem sys(m, inputs, s.pseudo_rigid);
  const pseudorigid::Body& body = m.mechanism.bodies[m.body];
  REQUIRE(sys.rotation_state() < 0);
  // Level, the hips at the legs' rest length above the ground, at rest.
  ode::Vec y = sys.initial_state();
  const double z = m.rest_length[0] - m.hip[0].z();
  for (int j = 0; j < 4; ++j) {
    const int c = 6 * (body.first_mass + j);
    y.segment<3>(c) = body.local[static_cast<size_t>(j)] + Vector3d(0.0, 0.0, z);
    y.segment<3>(c + 3).setZero();
  }
  for (size_t i = 0; i < m.hip.size(); ++i) {
    sys.foot_direction()[i] = -Vector3d::UnitZ();
    sys.land_foot(i, y);
  }
  Eigen::Matrix<double, 12, 12> K, M = Eigen::Matrix<double, 12, 12>::Zero();
  ode::Vec fp(sys.dimension()), fm(sys.dimension());
  for (int col = 0; col < 12; ++col) {
    const int at = 6 * (body.first_mass + col / 3) + col % 3;
    const double h = 1e-7;
    ode::Vec yp = y, ym = y;
    yp[at] += h;
    ym[at] -= h;
    sys.conservative_rhs(0.0, yp, fp);
    sys.conservative_rhs(0.0, ym, fm);
    for (int row = 0; row < 12; ++row) {
      const int r = 6 * (body.first_mass + row / 3) + 3 + row % 3;
      K(row, col) = -(fp[r] - fm[r]) / (2.0 * h);
    }
    M(col, col) = m.mechanism.masses[static_cast<size_t>(body.first_mass + col / 3)].mass;
  }
  const Eigen::Matrix<double, 12, 12> Ks = 0.5 * (K + K.transpose());
  CHECK((K - K.transpose()).norm() < 1e-5 * K.norm());  // a potential's Hessian
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(
      Ks, M, Eigen::EigenvaluesOnly);
  const double omega = std::sqrt(eig.eigenvalues().maxCoeff());
  CHECK(robot::quasi_static_omega(s, m, 1.0, -Vector3d::UnitZ()) == Approx(omega).epsilon(1e-4));
  CHECK(robot::quasi_static_omega(s, m) >= omega);
}

TEST_CASE("quasi-static feet: auto steps within the bound, a fixed step past it ends diverged",
          "[robot]") {
  const scene::Scene s = load({kRigid, kQuasi, "/simulation/duration=1"});
  const robot::RobotModel m = robot::build_robot(s);
  const double omega = robot::quasi_static_omega(s, m);
  const robot::RobotRunResult a = robot::simulate(s);
  const auto& c = a.monitors.method_choice;
  CHECK(c.method == ode::Method::kVerlet);
  // Stance: omega h = 0.6 rounded down to two digits (the ringing on the landed feet
  // resolved; 0.3 of the stability bound 2 / omega), unless the run missed its accuracy and
  // was rerun finer. Flight: nothing stiff acts on the rigid body, 5 ms.
  CHECK(c.h_fixed <= 0.6 / omega);
  if (c.reruns == 0) CHECK(c.h_fixed >= 0.55 / omega);
  CHECK(c.h_flight == Approx(5e-3));
  CHECK(a.run.status == reduced::RunStatus::kCompleted);
  const double bound = 2.0 / omega;
  const std::string past =
      "/pseudo_rigid/solver={\"method\":\"verlet\",\"h_fixed\":" + std::to_string(1.05 * bound) +
      "}";
  const robot::RobotRunResult r = robot::simulate(load({kRigid, kQuasi, past}));
  INFO(r.run.reason);
  CHECK(r.run.status == reduced::RunStatus::kDiverged);
  CHECK(r.run.reason.find("stability bound") != std::string::npos);
  CHECK(r.run.reason.find("rad/s") != std::string::npos);
  // A flight step past the four-mass body's own bound (its springs, 2 / omega = 2 ms).
  const robot::RobotRunResult f = robot::simulate(
      load({kQuasi, "/pseudo_rigid/body=\"four_masses\"",
            "/pseudo_rigid/solver={\"method\":\"verlet\",\"h_fixed\":2e-4,\"h_flight\":0.01}"}));
  INFO(f.run.reason);
  CHECK(f.run.status == reduced::RunStatus::kDiverged);
  CHECK(f.run.reason.find("flight step 0.01 s") != std::string::npos);
  CHECK(f.run.reason.find("own stability bound") != std::string::npos);
}

// A passive drop (no actuators) onto tilted feet: E + D - W (D: the energy the leg dampers and
// the feet's creep released; W: the hips' placing in the air) stays at its start at every
// sample, within 1e-3 of the energy scale (measured 9e-5). (Asked to run after a moving
// setpoint, the passive robot collapses within 0.85 s on either feet, and on the quasi-static
// feet the balance then drifts by 1.4e-2 of the scale as the feet slide out.)
TEST_CASE("quasi-static feet: a passive drop keeps its energy balance", "[robot]") {
  const std::string body =
      GENERATE(std::string(kRigid), std::string("/pseudo_rigid/body=\"four_masses\""));
  INFO(body);
  const robot::RobotRunResult r =
      robot::simulate(load({body, kQuasi, "/pseudo_rigid/actuators=false",
                            "/initial/attitude_deg=[3,2,0]", "/initial/position=[0,0,0.4]",
                            "/controller/setpoint/velocity=[0,0,0]", "/simulation/duration=1.5"}));
  REQUIRE(r.samples.size() > 100);
  CHECK(r.run.status != reduced::RunStatus::kDiverged);
  auto balance = [](const robot::RobotSample& smp) {
    return smp.energies.total() + smp.dissipated - smp.actuator_work;  // (W: the hips' placing)
  };
  double worst = 0.0;
  for (const auto& smp : r.samples) {
    CHECK(std::isfinite(smp.energies.total()));
    worst = std::max(worst, std::abs(balance(smp) - balance(r.samples.front())));
  }
  CHECK(worst <= 1e-3 * r.monitors.energy_scale);
  CHECK(r.samples.back().dissipated > 0.1 * r.monitors.energy_scale);  // the dampers worked
}

// pr_running on quasi-static feet with "method": "auto" (the default) against the 1 g feet at
// a step fine enough for their ringing (Verlet 1.5e-5 s; 3e-5 s is still 5 % off in the
// first stride's contact time), stride by stride over the first 10 strides, on either body.
// Measured over 10 s: rigid body apex within 0.45 %, contact time (first foot down to the
// last foot up) within 1.4 %, touchdown roll and pitch within 0.86 deg; four masses 0.56 %,
// 0.9 %, 0.50 deg. The attitude is the two models' difference (the feet's inertia in flight,
// next test), bounded here so that it cannot grow.
TEST_CASE("quasi-static feet: pr_running stride by stride against the 1 g feet", "[robot][heavy]") {
  const std::string body =
      GENERATE(std::string(kRigid), std::string("/pseudo_rigid/body=\"four_masses\""));
  INFO(body);
  const robot::RobotRunResult ref =
      robot::simulate(load({body, "/simulation/duration=2.6",
                            "/pseudo_rigid/solver={\"method\":\"verlet\",\"h_fixed\":1.5e-5}"}));
  const robot::RobotRunResult q = robot::simulate(load({body, kQuasi, "/simulation/duration=2.6"}));
  REQUIRE(ref.run.strides.size() >= 10);
  REQUIRE(q.run.strides.size() >= 10);
  for (size_t k = 0; k < 10; ++k) {
    const auto& a = ref.run.strides[k];
    const auto& b = q.run.strides[k];
    INFO("stride " << k);
    CHECK(b.apex_height == Approx(a.apex_height).epsilon(0.01));
    CHECK(q.stride_contact[k] == Approx(ref.stride_contact[k]).epsilon(0.02));
    CHECK(std::abs(b.euler123.x() - a.euler123.x()) < 1.0 * M_PI / 180.0);
    CHECK(std::abs(b.euler123.y() - a.euler123.y()) < 1.0 * M_PI / 180.0);
  }
}

// The quasi-static feet are the massless limit of the foot masses: with the stance attitude
// feedback off (whose switch on three grounded legs differs between the two, see
// docs/full_model.md#quasi-static-feet), the first 10 strides' touchdown attitude approaches
// the quasi-static feet's as the feet lighten (measured over 10 s: 1.18 deg at 1 g, 0.74 at
// 0.3 g, 0.27 at 0.1 g: a foot mass swung into place in flight turns the body back, four 1 g
// feet about 0.3 m from the CoM adding 3.6e-4 kg m^2 to its 0.0074 about x), and the apex and
// the contact time agree within 1 % and 2 %.
TEST_CASE("quasi-static feet: the massless limit of the foot masses", "[robot][heavy]") {
  const std::string no_fb = R"(/pseudo_rigid/stance_attitude={"kp":[0,0],"kd":[0,0]})";
  const std::string shorter = "/simulation/duration=2.6";
  const robot::RobotRunResult q =
      robot::simulate(load({kRigid, kQuasi, no_fb, shorter,
                            R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-4})"}));
  REQUIRE(q.run.strides.size() >= 10);
  auto worst_attitude = [&](double foot_mass, double* apex, double* contact) {
    const robot::RobotRunResult m = robot::simulate(
        load({kRigid, no_fb, shorter, "/pseudo_rigid/foot_mass=" + std::to_string(foot_mass),
              R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-5})"}));
    REQUIRE(m.run.strides.size() >= 10);
    double w = 0.0;
    *apex = *contact = 0.0;
    for (size_t k = 0; k < 10; ++k) {
      const auto& a = m.run.strides[k];
      const auto& b = q.run.strides[k];
      w = std::max(w, (b.euler123 - a.euler123).head<2>().cwiseAbs().maxCoeff() * 180.0 / M_PI);
      *apex = std::max(*apex, std::abs(b.apex_height / a.apex_height - 1.0));
      *contact = std::max(*contact, std::abs(q.stride_contact[k] / m.stride_contact[k] - 1.0));
    }
    return w;
  };
  double apex = 0.0, contact = 0.0;
  const double at_1g = worst_attitude(1e-3, &apex, &contact);
  const double at_03g = worst_attitude(3e-4, &apex, &contact);
  const double at_01g = worst_attitude(1e-4, &apex, &contact);
  INFO("touchdown attitude differences [deg]: " << at_1g << ", " << at_03g << ", " << at_01g);
  CHECK(at_03g < at_1g);
  CHECK(at_01g < at_03g);
  CHECK(at_01g < 0.3);
  CHECK(apex < 0.01);
  CHECK(contact < 0.02);
}

// Case 6 (a passive drop onto frictionless ground, locked stance hips: each pinned foot held
// by its leg's line, two slot normals, and sliding freely along the ground) on quasi-static
// feet against the 1 g feet at Verlet 1.5e-5 s, bounce by bounce over the first 10, on either
// body. The contact time is read off the samples (sampled_contact_times; the foot masses have
// no events with locked hips), sampled every 0.2 ms. Measured: four masses apex within
// 0.79 %, contact time within 1.3 %; rigid body 0.50 %, 1.3 %; attitude level in both (the
// drop is symmetric). The apex gap grows bounce by bounce: the foot masses lose their impact
// energy at every landing (1 g at about 1.7 m/s per foot, and their contact damper), the
// massless feet nothing.
TEST_CASE("quasi-static feet: case 6 bounce by bounce against the 1 g feet", "[robot][heavy]") {
  const std::string body =
      GENERATE(std::string(kRigid), std::string("/pseudo_rigid/body=\"four_masses\""));
  INFO(body);
  const std::string fine_samples = "/simulation/sample_interval=0.0002";
  auto case6 = [&](std::vector<std::string> set) {
    set.push_back(body);
    set.push_back(fine_samples);
    return robot::simulate(load_shipped("case6_pr_drop", set));
  };
  const robot::RobotRunResult ref =
      case6({"/pseudo_rigid/solver={\"method\":\"verlet\",\"h_fixed\":1.5e-5}"});
  const robot::RobotRunResult q = case6({kQuasi});
  REQUIRE(q.run.status == reduced::RunStatus::kCompleted);
  const std::vector<double> cr = robot::sampled_contact_times(ref);
  const std::vector<double> cq = robot::sampled_contact_times(q);
  REQUIRE(ref.run.strides.size() >= 10);
  REQUIRE(q.run.strides.size() >= 10);
  REQUIRE(cr.size() >= 10);
  REQUIRE(cq.size() >= 10);
  for (size_t k = 0; k < 10; ++k) {
    const auto& a = ref.run.strides[k];
    const auto& b = q.run.strides[k];
    INFO("bounce " << k);
    CHECK(b.apex_height == Approx(a.apex_height).epsilon(0.01));
    CHECK(cq[k] == Approx(cr[k]).epsilon(0.02));
    CHECK(std::abs(b.euler123.x() - a.euler123.x()) < 0.3 * M_PI / 180.0);
    CHECK(std::abs(b.euler123.y() - a.euler123.y()) < 0.3 * M_PI / 180.0);
  }
  // Frictionless, undamped legs: what the quasi-static feet dissipate is their relaxation's
  // round-off; the balance holds to 1e-3 of the scale at every sample (measured 1e-5).
  double worst = 0.0;
  auto balance = [](const robot::RobotSample& smp) {
    return smp.energies.total() + smp.dissipated - smp.actuator_work;
  };
  for (const auto& smp : q.samples) {
    worst = std::max(worst, std::abs(balance(smp) - balance(q.samples.front())));
  }
  CHECK(worst <= 1e-3 * q.monitors.energy_scale);
}

// The sampled contact times on a hand-made record (samples every 1 ms): a hop whose feet touch
// at 0.1045 s, ring off the ground once within the stance and leave at 0.2985 s, then a brief
// tap after the apex, then a second stance (0.5005 .. 0.6005 s) still under way at the end of
// the next stretch's apex, and a last one the record ends in. Each end is halfway between the
// samples around it.
TEST_CASE("quasi-static feet: contact times read off the samples", "[robot]") {
  robot::RobotRunResult r;
  auto contact = [](double t) {
    const bool ring = t > 0.150 && t < 0.153;  // one foot rings off, all lift
    const bool first = t > 0.1045 && t < 0.2985 && !ring;
    const bool tap = t > 0.3500 && t < 0.3520;  // after the apex at 0.34 s
    const bool second = t > 0.5005 && t < 0.6005;
    const bool last = t > 0.9005;
    return first || tap || second || last;
  };
  auto rising = [](double t) {  // apexes at 0.34, 0.75 s; lowest points at 0.2, 0.55, 0.95 s
    return (t > 0.2 && t < 0.34) || (t > 0.55 && t < 0.75) || t > 0.95;
  };
  for (int k = 0; k <= 1000; ++k) {
    const double t = 1e-3 * k;
    robot::RobotSample smp;
    smp.t = t;
    smp.normal_force = {0.0, contact(t) ? 3.0 : 0.0, 0.0, 0.0};
    const bool ringing = t > 0.150 && t < 0.153;  // the foot within 0.1 mm of the ground
    smp.foot_z = {0.05, contact(t) ? 0.0 : ringing ? 1e-4 : 0.01, 0.05, 0.05};
    reduced::Sample traj;
    traj.t = t;
    traj.position = traj.euler123 = traj.omega = traj.setpoint = Vector3d::Zero();
    traj.velocity = Vector3d(0.0, 0.0, rising(t) ? 1.0 : -1.0);
    r.samples.push_back(smp);
    r.run.trajectory.push_back(traj);
  }
  const std::vector<double> c = robot::sampled_contact_times(r);
  REQUIRE(c.size() == 2);
  CHECK(c[0] == Approx(0.2985 - 0.1045).margin(1e-12));  // the ringing and the tap left out
  CHECK(c[1] == Approx(0.6005 - 0.5005).margin(1e-12));
}

namespace {

/// The worst sampled departure of E + D - W from its start, relative to the energy scale.
double worst_balance(const robot::RobotRunResult& r) {
  auto balance = [](const robot::RobotSample& smp) {
    return smp.energies.total() + smp.dissipated - smp.actuator_work;
  };
  double worst = 0.0;
  for (const auto& smp : r.samples) {
    worst = std::max(worst, std::abs(balance(smp) - balance(r.samples.front())));
  }
  return worst / r.monitors.energy_scale;
}

std::string verlet(double h, double h_flight) {
  return "/pseudo_rigid/solver={\"method\":\"verlet\",\"h_fixed\":" + std::to_string(h) +
         ",\"h_flight\":" + std::to_string(h_flight) + "}";
}

}  // namespace

// A running robot's energy balance (a conservation law: E + D - W, D the dampers' and the
// creep's release and what lifted feet take away, W the actuators' work through the kicks)
// on quasi-static feet converges with the stance step: pr_running on the rigid body, 3 s,
// measured 7.2e-4 of the scale at 6.1e-4 s (near the stability bound), 7.4e-5 at 3e-4 s. (At
// 6e-4 s it drifted 4.8e-3, first order in h, while the work was booked with the actuator
// forces at the steps' final momenta and a lifted foot's leg energy was interpolated in E.)
TEST_CASE("quasi-static feet: the running robot's energy balance converges with the step",
          "[robot]") {
  const robot::RobotRunResult a =
      robot::simulate(load({kRigid, kQuasi, "/simulation/duration=3", verlet(6.1e-4, 5e-3)}));
  const robot::RobotRunResult b =
      robot::simulate(load({kRigid, kQuasi, "/simulation/duration=3", verlet(3e-4, 5e-3)}));
  REQUIRE(a.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(b.run.status == reduced::RunStatus::kCompleted);
  REQUIRE(a.run.strides.size() >= 12);
  const double wa = worst_balance(a), wb = worst_balance(b);
  INFO("balance " << wa << " at 6.1e-4 s, " << wb << " at 3e-4 s");
  CHECK(wa <= 1e-3);
  CHECK(wb <= wa / 4.0);  // at least second order
}

// Flight on its own step: with every foot in the air and every hip locked only gravity acts
// on the rigid body, which Verlet integrates exactly but for the free rotation's splitting, so
// flight at 5 ms runs the same robot as flight at the stance step: over 3 s of pr_running every
// stride's apex and touchdown time agree to 1e-6 (relative; measured within 1.2e-7 and 3e-7 s,
// the rotation's splitting and the touchdowns located on the dense output), and the balance to
// 1e-6 of the scale, in a third of the steps.
TEST_CASE("quasi-static feet: flight on its own step changes nothing but the steps", "[robot]") {
  const robot::RobotRunResult a =
      robot::simulate(load({kRigid, kQuasi, "/simulation/duration=3", verlet(3e-4, 0.0)}));
  const robot::RobotRunResult b =
      robot::simulate(load({kRigid, kQuasi, "/simulation/duration=3", verlet(3e-4, 5e-3)}));
  REQUIRE(a.run.strides.size() == b.run.strides.size());
  REQUIRE(a.run.strides.size() >= 12);
  for (size_t k = 0; k < a.run.strides.size(); ++k) {
    INFO("stride " << k);
    CHECK(b.run.strides[k].apex_height == Approx(a.run.strides[k].apex_height).epsilon(1e-6));
    CHECK(b.run.strides[k].t_touchdown == Approx(a.run.strides[k].t_touchdown).epsilon(1e-6));
  }
  CHECK(std::abs(worst_balance(a) - worst_balance(b)) <= 1e-6);
  CHECK(3 * b.run.cost.solver.steps_accepted < 2 * a.run.cost.solver.steps_accepted);
  // A flight step on the foot masses does nothing, and says so.
  const scene::Scene mass = load({kRigid, verlet(1.5e-4, 5e-3)});
  const std::vector<std::string> unused = io::unused_settings(mass);
  CHECK(std::find(unused.begin(), unused.end(), "/pseudo_rigid/solver/h_flight") != unused.end());
  const std::vector<std::string> used =
      io::unused_settings(load({kRigid, kQuasi, verlet(3e-4, 5e-3)}));
  CHECK(std::find(used.begin(), used.end(), "/pseudo_rigid/solver/h_flight") == used.end());
}
