// The full model's leg placement for free stance hips (sim/robot/leg_placement.hpp): the
// inverted-pendulum rule against an independent integration of its own stance model, and its
// small-stance limit against the linear neutral-point rule.
#include <catch2/catch.hpp>
#include <cmath>

#include <string>

#include "io/load/input_error.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/robot/leg_placement.hpp"

using Eigen::Vector3d;
using pronk::robot::detail::free_leg_direction;
using pronk::robot::detail::pendulum_leg_direction;

namespace {

/// The hip's horizontal offset from its foot over a stance of T seconds, x'' = w^2 x (RK4, n
/// steps), from x0 and v0: returns the speed at the end.
double lp_pendulum_speed(double w, double T, double x0, double v0, int n = 20000) {
  double x = x0, v = v0;
  const double h = T / n;
  for (int k = 0; k < n; ++k) {
    const double k1x = v, k1v = w * w * x;
    const double k2x = v + 0.5 * h * k1v, k2v = w * w * (x + 0.5 * h * k1x);
    const double k3x = v + 0.5 * h * k2v, k3v = w * w * (x + 0.5 * h * k2x);
    const double k4x = v + h * k3v, k4v = w * w * (x + h * k3x);
    x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
  return v;
}

}  // namespace

TEST_CASE("pendulum placement delivers the impulse asked on its own stance model", "[placement]") {
  // pr_running's robot at 1.5 and 2.2 kg and a light one: stances of 0.07-0.12 s, wT 0.9-1.7.
  struct Case {
    double m, T, leg, Pz;
    Vector3d v0;
    Eigen::Vector2d Ph;
  };
  const Case cases[] = {{2.2, 0.112, 0.21, 11.13, {0.192, 0.0, -1.98}, {0.476, 0.0}},
                        {1.5, 0.074, 0.21, 7.1, {0.3, 0.05, -1.98}, {-0.2, 0.1}},
                        {0.5, 0.06, 0.15, 1.8, {0.2, -0.1, -1.5}, {0.05, -0.03}}};
  for (const Case& c : cases) {
    const Vector3d P(c.Ph.x(), c.Ph.y(), c.Pz);
    const Vector3d d =
        pendulum_leg_direction(P, c.v0, c.T, c.leg, c.m, 1.0, false, Vector3d::Zero());
    const double w = std::sqrt(c.Pz / (c.T * c.m * c.leg));
    INFO("m " << c.m << " wT " << w * c.T);
    CHECK(d.norm() == Approx(1.0).epsilon(1e-12));
    CHECK(d.z() < 0.0);
    for (int k = 0; k < 2; ++k) {
      const double x0 = -c.leg * d[k];  // the hip's offset from its foot at touchdown
      const double v1 = lp_pendulum_speed(w, c.T, x0, c.v0[k]);
      CHECK(c.m * (v1 - c.v0[k]) == Approx(c.Ph[k]).margin(1e-9));
    }
  }
}

TEST_CASE("pendulum placement becomes the linear neutral-point rule for short stances",
          "[placement]") {
  // wT -> 0: r = T v0 / 2 - leg P_h / P_z, the linear rule with v0 for its mean speed; the
  // difference is second order in wT (and in P_h / P_z, the linear rule's |P|).
  const double m = 1.5, leg = 0.21, Pz = 7.0;
  const Vector3d v0(0.3, -0.1, -2.0);
  const Vector3d P(0.002, -0.001, Pz);
  double last = 1.0;
  for (double T : {4e-3, 2e-3, 1e-3}) {
    const double w = std::sqrt(Pz / (T * m * leg));
    const Vector3d a = pendulum_leg_direction(P, v0, T, leg, m, 1.0, false, Vector3d::Zero());
    const Vector3d b = free_leg_direction(P, v0, T, leg, 1.0, false, Vector3d::Zero());
    const double diff = (a - b).head<2>().norm() / b.head<2>().norm();
    INFO("T " << T << " wT " << w * T << " relative difference " << diff);
    CHECK(diff < 0.2 * (w * T) * (w * T) + 1e-6);
    CHECK(diff < last);
    last = diff;
  }
}

TEST_CASE("pendulum placement: held roll puts the leg along the takeoff velocity in y",
          "[placement]") {
  const Vector3d P(0.1, 0.3, 9.0), v0(0.2, 0.1, -2.0), vt(0.25, 0.2, 2.0);
  const Vector3d a = pendulum_leg_direction(P, v0, 0.1, 0.21, 1.5, 1.0, true, vt);
  CHECK(a.y() == Approx(-vt.y() / std::hypot(vt.y(), vt.z())).epsilon(1e-12));
  // The leg's angle from the vertical stays within max_angle.
  const Vector3d far = pendulum_leg_direction(Vector3d(5.0, 0.0, 9.0), v0, 0.1, 0.21, 1.5, 0.3,
                                              false, Vector3d::Zero());
  CHECK(std::asin(far.head<2>().norm()) == Approx(0.3).epsilon(1e-12));
}

TEST_CASE("hip_rotation: pendulum by default, true is the neutral-point rule, bad values refused",
          "[placement]") {
  const std::string tripod = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/family/tripod.json";
  auto load = [&](const std::string& value) {
    return pronk::io::load_scene(tripod, {"/pseudo_rigid={\"hip_rotation\": " + value + "}"})
        .pseudo_rigid;
  };
  const auto d = pronk::io::load_scene(tripod).pseudo_rigid;
  CHECK(d.hip_rotation);
  CHECK(d.pendulum_placement);
  CHECK(load("\"pendulum\"").pendulum_placement);
  CHECK_FALSE(load("\"neutral_point\"").pendulum_placement);
  CHECK_FALSE(load("true").pendulum_placement);
  CHECK(load("true").hip_rotation);
  CHECK_FALSE(load("false").hip_rotation);
  // The resolved scene writes "pendulum" or the boolean, and reads back the same.
  CHECK(pronk::io::pseudo_rigid_to_json(d)["hip_rotation"] == "pendulum");
  CHECK(pronk::io::pseudo_rigid_to_json(load("\"neutral_point\""))["hip_rotation"] == true);
  for (const char* bad : {"3", "\"raibert\""}) {
    INFO(bad);
    try {
      load(bad);
      FAIL("hip_rotation " << bad << " accepted");
    } catch (const pronk::io::InputError& e) {
      CHECK(e.pointer() == "/pseudo_rigid/hip_rotation");
      CHECK(e.file().find("tripod.json") != std::string::npos);
    }
  }
}

TEST_CASE("held roll is placed across the body as it is headed", "[placement]") {
  // The whole problem turned about the vertical by psi, heading psi: the legs come out turned by
  // psi (the rule is the same in the body's own axes), for both placement rules.
  const Vector3d P(0.12, -0.05, 9.0), v0(0.3, 0.15, -1.9), v_takeoff(0.31, 0.12, 1.9);
  for (const double psi : {0.05, -0.4, 1.3}) {
    const Eigen::Matrix3d Rz = Eigen::AngleAxisd(psi, Vector3d::UnitZ()).toRotationMatrix();
    const Vector3d a = pendulum_leg_direction(P, v0, 0.09, 0.2, 2.0, 0.6, true, v_takeoff, 0.0);
    const Vector3d b =
        pendulum_leg_direction(Rz * P, Rz * v0, 0.09, 0.2, 2.0, 0.6, true, Rz * v_takeoff, psi);
    CHECK((b - Rz * a).norm() < 1e-12);
    const Vector3d c = free_leg_direction(P, v0, 0.09, 0.2, 0.6, true, v_takeoff, 0.0);
    const Vector3d e =
        free_leg_direction(Rz * P, Rz * v0, 0.09, 0.2, 0.6, true, Rz * v_takeoff, psi);
    CHECK((e - Rz * c).norm() < 1e-12);
    // Across the body the foot is put along the takeoff velocity (no neutral point).
    const Vector3d across = Rz * Vector3d::UnitY();
    const double v_across = (Rz * v_takeoff).dot(across);
    CHECK(b.dot(across) == Approx(-v_across / std::hypot(v_across, v_takeoff.z())).margin(1e-12));
  }
}

TEST_CASE("legs turned apart deliver the yaw asked and no net push", "[placement]") {
  // Three, four and six hips, symmetric and not: each leg carries Pz / n of the vertical
  // impulse along itself, so its horizontal push is -(Pz / n) (foot - hip) / leg; the pushes'
  // moment about the vertical must be Hz and their sum the common leg's.
  using pronk::robot::detail::yaw_leg_directions;
  const std::vector<std::vector<Eigen::Vector2d>> robots = {
      {{0.15, 0.0}, {-0.08, 0.13}, {-0.08, -0.13}},
      {{0.2, 0.1}, {0.2, -0.1}, {-0.2, 0.1}, {-0.2, -0.1}},
      {{0.25, 0.12}, {0.25, -0.12}, {0.0, 0.15}, {0.0, -0.15}, {-0.25, 0.12}, {-0.22, -0.1}}};
  const double leg = 0.25, Pz = 8.0;
  const Vector3d d = Vector3d(0.05, -0.02, -1.0).normalized();
  for (const auto& hips : robots) {
    for (const double Hz : {0.004, -0.01}) {
      const auto u = yaw_leg_directions(d, hips, Hz, Pz, leg, 0.6);
      REQUIRE(u.size() == hips.size());
      const double n = static_cast<double>(hips.size());
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (const auto& h : hips) centre += h / n;
      // About the hips' centre (the parallel push has no moment there), and the turned-apart
      // part alone about any point.
      double moment = 0.0, moment_apart = 0.0;
      Eigen::Vector2d sum = Eigen::Vector2d::Zero(), common = Eigen::Vector2d::Zero();
      for (size_t i = 0; i < hips.size(); ++i) {
        CHECK(u[i].norm() == Approx(1.0).epsilon(1e-12));
        const Eigen::Vector2d push = -(Pz / n) * u[i].head<2>();  // (foot - hip) / leg = u
        const Eigen::Vector2d apart = push + (Pz / n) * d.head<2>();
        const Eigen::Vector2d lever = hips[i] - centre;
        const Eigen::Vector2d lever_any = hips[i] + Eigen::Vector2d(0.3, -0.7);
        moment += lever.x() * push.y() - lever.y() * push.x();
        moment_apart += lever_any.x() * apart.y() - lever_any.y() * apart.x();
        sum += push;
        common += -(Pz / n) * d.head<2>();
      }
      CHECK(moment == Approx(Hz).margin(1e-15));
      // With the exact strut law (each leg's vertical share Pz / n, its push along itself,
      // horizontal -(Pz / n) u_h / |u_z|) the moment is Hz to within the small-angle error.
      double moment_exact = 0.0;
      for (size_t i = 0; i < hips.size(); ++i) {
        const Eigen::Vector2d push = -(Pz / n) * u[i].head<2>() / -u[i].z();
        const Eigen::Vector2d lever = hips[i] - centre;
        moment_exact += lever.x() * push.y() - lever.y() * push.x();
      }
      CHECK(moment_exact == Approx(Hz).epsilon(0.02));
      CHECK(moment_apart == Approx(Hz).margin(1e-15));
      CHECK((sum - common).norm() < 1e-14);
    }
  }
  // No yaw asked: the legs stay parallel.
  for (const auto& ui : yaw_leg_directions(d, robots[1], 0.0, Pz, leg, 0.6)) {
    CHECK((ui - d).norm() == 0.0);
  }
}
