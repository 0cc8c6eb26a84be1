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
