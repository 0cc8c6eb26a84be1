// The reduced (impulse and pulse) models at their extremes (docs/models.md): each case
// ends accurate (against conservation laws, an exact scaling law or the
// controller's own targets) or with a status, reason or warning the run
// reports; never NaN, never an unbounded run.
#include <cmath>
#include <cstdio>
#include <string>

#include <catch2/catch.hpp>

#include "io/write/run_output.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/math/rotation.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/reduced/simulator.hpp"
#include "tests/extremes/extremes_support.hpp"
#include "tests/support/scenes.hpp"

using namespace pronk;
using Eigen::Matrix3d;
using Eigen::Vector3d;
namespace ex = pronk::test::extremes;

namespace {

constexpr double kDeg = M_PI / 180.0;

/// A body in zero gravity that never touches down: torque-free flight only.
scene::Scene free_flight(const Vector3d& i, const Vector3d& w_body, double duration,
                         scene::AttitudeFormulation formulation) {
  scene::Scene s;
  s.gravity = 0.0;
  s.attitude = formulation;
  s.body.inertia = i.asDiagonal();
  s.initial.position = Vector3d(0, 0, 1);
  s.initial.attitude = math::euler_to_quat(Vector3d(0.1, -0.05, 0.2), math::EulerSet::k123);
  s.initial.angular_velocity = w_body;
  s.simulation.duration = duration;
  s.simulation.fall_max_tilt = M_PI;  // tumbling is the point here, not a fall
  s.simulation.solver.h_max = 0.01;
  s.simulation.solver.max_steps = 1000000;
  return s;
}

/// Relative changes of rotational energy and world angular momentum over a free flight.
struct Conservation {
  double energy, momentum;
};
Conservation conservation(const scene::Scene& s, const reduced::RunResult& r) {
  const Matrix3d I = s.body.inertia;
  const Vector3d w0 = s.initial.angular_velocity;
  const Vector3d l0 = s.initial.attitude.toRotationMatrix() * (I * w0);
  const Vector3d l1 = r.final_attitude.toRotationMatrix() * (I * r.final_omega);
  const double e0 = 0.5 * w0.dot(I * w0), e1 = 0.5 * r.final_omega.dot(I * r.final_omega);
  return {std::abs(e1 - e0) / e0, (l1 - l0).norm() / l0.norm()};
}

}  // namespace

TEST_CASE("extreme: duty cycle 1 %..90 % in the pulse model completes or falls with a reason",
          "[extremes][reduced]") {
  // Stance duration T for a nominal duty d: T = d / (1 - d) x the ballistic flight time.
  // The pulse-aware hop law (legged_pulse_duty50) holds the apex exactly while the stance
  // fits above the ground; the seed's law (case 3) loses the gait above ~30 % (Ridgely 2001,
  // §2.6.1). At 70-90 % a stance long enough sinks the CoM through the ground: "fell", with when.
  const double flight = 2.0 * std::sqrt(2.0 * 9.81 * 0.2) / 9.81;  // [s]
  for (double duty : {0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 0.9}) {
    const double t_stance = duty / (1.0 - duty) * flight;
    for (const bool aware : {true, false}) {
      INFO((aware ? "pulse-aware law" : "seed law") << ", duty " << duty);
      const auto s = test::load_shipped(
          aware ? "legged_pulse_duty50" : "case3_legged_pulse",
          {"/pulse/duration=" + std::to_string(t_stance), "/simulation/duration=10"});
      const auto r = reduced::simulate(s);
      const auto met = reduced::compute_metrics(s, r);
      INFO(to_string(r.status) << ": " << r.reason);
      CHECK(ex::all_finite(r));
      REQUIRE(r.status != reduced::RunStatus::kDiverged);
      if (r.status == reduced::RunStatus::kFell) {
        CHECK(r.reason.find(" at t = ") != std::string::npos);
        CHECK((r.reason.find("fell below") != std::string::npos ||
               r.reason.find("tilted past") != std::string::npos));
      } else {
        CHECK(met.mean_duty == Approx(duty).margin(0.002));
        if (aware) CHECK(met.max_apex_error < 1e-9);
      }
      const bool completes = aware ? duty <= 0.5 : duty <= 0.3;
      if (completes) CHECK(r.status == reduced::RunStatus::kCompleted);
      if (duty >= 0.9) CHECK(r.status == reduced::RunStatus::kFell);
    }
  }
}

TEST_CASE("extreme: near-degenerate inertia in the reduced model", "[extremes][reduced]") {
  SECTION("flat plate and slender rods: torque-free motion conserves energy and momentum") {
    for (const Vector3d& i : {Vector3d(0.1, 0.2, 0.3), Vector3d(1e-6, 1.0, 1.0),
                              Vector3d(1e-9, 1.0, 1.0), Vector3d(1e-4, 1.0, 1.01)}) {
      INFO("I = " << i.transpose());
      const auto s =
          free_flight(i, Vector3d(0.5, 1.0, 0.3), 5.0, scene::AttitudeFormulation::kQuaternion);
      const auto r = reduced::simulate(s);
      REQUIRE(r.status == reduced::RunStatus::kCompleted);
      CHECK(ex::all_finite(r));
      const Conservation c = conservation(s, r);
      // Measured <= 2e-13, except 1.9e-8 / 9.6e-9 for the non-axisymmetric rod, whose
      // axial rate swings at (Izz - Iyy)/Ixx = 100 x the tumbling rate (rtol 1e-9).
      CHECK(c.energy < 1e-7);
      CHECK(c.momentum < 1e-7);
      CHECK(r.cost.solver.steps_accepted < 100000);
    }
  }
  SECTION("the exact limits are bad input with the offending value") {
    const auto bad = [](const std::string& inertia) {
      try {
        test::load_shipped("case1_body_only", {"/body/inertia=" + inertia});
      } catch (const io::InputError& e) {
        CHECK(e.pointer() == "/body/inertia");
        return std::string(e.what());
      }
      FAIL("accepted " << inertia);
      return std::string();
    };
    CHECK(bad("[0, 1, 1]").find("positive principal moments") != std::string::npos);
    CHECK(bad("[0.1, 0.2, 0.31]").find("Izz = 0.31 > 0.3") != std::string::npos);
    // The flat plate itself (Izz = Ixx + Iyy) is a valid rigid body for the reduced model.
    CHECK_NOTHROW(test::load_shipped("case1_body_only", {"/body/inertia=[0.1, 0.2, 0.3]"}));
  }
}

TEST_CASE("extreme: attitude through 90 deg and beyond, exact vs small-angle (warns)",
          "[extremes][reduced]") {
  const Vector3d i(0.0074, 0.0106, 0.0164);
  const Vector3d w0(0.3, 6.0, 0.5);  // end over end about the pitch axis, ~2 turns in 2 s
  SECTION("quaternion: exact through gimbal lock, no warning") {
    const auto s = free_flight(i, w0, 2.0, scene::AttitudeFormulation::kQuaternion);
    const auto r = reduced::simulate(s);
    REQUIRE(r.status == reduced::RunStatus::kCompleted);
    CHECK(ex::all_finite(r));
    const Conservation c = conservation(s, r);
    CHECK(c.energy < 1e-9);
    CHECK(c.momentum < 1e-9);
    double max_pitch = 0.0;
    for (const auto& smp : r.trajectory)
      max_pitch = std::max(max_pitch, std::abs(smp.euler123.y()));
    CHECK(max_pitch > 80.0 * kDeg);  // the 1-2-3 pitch folds back at +-90 deg
    CHECK(r.warnings.empty());
  }
  SECTION("small-angle Euler 1-2-3: wrong, and the run says so once") {
    const auto s = free_flight(i, w0, 2.0, scene::AttitudeFormulation::kSmallAngleEuler123);
    const auto r = reduced::simulate(s);
    REQUIRE(r.status == reduced::RunStatus::kCompleted);
    CHECK(ex::all_finite(r));
    CHECK(conservation(s, r).momentum > 0.1);  // measured 0.65: not physics
    REQUIRE(r.warnings.size() == 1);
    CHECK(r.warnings.at("small_angle_range_exceeded") == 1);  // one flight segment
    const auto summary = io::run_summary_json(s, r, reduced::compute_metrics(s, r));
    CHECK(summary["warnings"]["small_angle_range_exceeded"] == 1);
  }
  SECTION("small-angle running: silent within +-15 deg, warned beyond") {
    const auto quiet = reduced::simulate(test::load_shipped(
        "case1_body_only", {"/attitude=small_angle_euler123", "/initial/attitude_deg/0=10"}));
    CHECK(quiet.status == reduced::RunStatus::kCompleted);
    CHECK(quiet.warnings.count("small_angle_range_exceeded") == 0);
    const auto loud = reduced::simulate(test::load_shipped(
        "case1_body_only", {"/attitude=small_angle_euler123", "/initial/attitude_deg/0=20"}));
    CHECK(loud.status == reduced::RunStatus::kCompleted);
    CHECK(loud.warnings.count("small_angle_range_exceeded") == 1);
    // The same start in the exact formulation does not warn.
    const auto exact =
        reduced::simulate(test::load_shipped("case1_body_only", {"/initial/attitude_deg/0=20"}));
    CHECK(exact.warnings.empty());
  }
}

TEST_CASE("extreme: 1000-stride runs keep energy and setpoint drift bounded and reported",
          "[extremes][reduced]") {
  reduced::RunOptions o;
  o.record_trajectory = false;
  // The run ends at 1000 strides; its duration only has to be long enough. (Read with the
  // default 5 ms samples, 1e6 s would be 2e8 samples, which the loader refuses.)
  const std::vector<std::string> long_run = {"/simulation/duration=1e6",
                                             "/simulation/max_strides=1000",
                                             "/simulation/sample_interval=0.1"};
  for (const char* name : {"case1_body_only", "case2_legged_impulse", "case3_legged_pulse"}) {
    INFO(name);
    const auto s = test::load_shipped(name, long_run);
    const auto r = reduced::simulate(s, o);
    const auto met = reduced::compute_metrics(s, r);
    REQUIRE(r.status == reduced::RunStatus::kCompleted);
    CHECK(r.reason == "reached 1000 strides");
    CHECK(r.strides.size() == 1000);
    CHECK(ex::all_finite(r));
    CHECK(r.t_end > 400.0);  // past t = 256 s, where event location used to slip
    // Flight energy is conserved by the physics: its drift is integration error.
    CHECK(r.monitors.max_flight_energy_drift < 1e-9);
    CHECK(r.monitors.max_event_residual < 1e-9);
    CHECK(r.monitors.max_quaternion_norm_error < 1e-9);
    // Setpoint tracking does not drift over 400 s of running after a moving setpoint.
    CHECK(std::abs(met.final_x_error) < 1e-6);
    CHECK(std::abs(met.final_y_error) < 1e-6);
    CHECK(std::abs(met.last_apex_error) < 1e-3);  // the seed law's pulse misses by ~2e-4 m
    CHECK(met.settle_strides >= 0);
    // Body-only impulses hit every apex exactly (the legged robot cannot push along body y).
    if (s.legs.body_only) CHECK(met.max_apex_error < 1e-8);
    const auto summary = io::run_summary_json(s, r, met);
    CHECK(summary["monitors"]["max_flight_energy_drift"].get<double>() ==
          r.monitors.max_flight_energy_drift);
  }
  // The untuned 50 %-duty scene is unstable (stride-map radius > 1): 1000 strides expose it
  // as a fall with its time, not as NaN.
  const auto s = test::load_shipped("legged_pulse_duty50", long_run);
  const auto r = reduced::simulate(s, o);
  CHECK(r.status == reduced::RunStatus::kFell);
  CHECK(r.reason.find("fell below") != std::string::npos);
  CHECK(r.strides.size() < 1000);
  CHECK(ex::all_finite(r));
}

TEST_CASE("extreme: masses 1e-4..1e3 kg in the reduced model", "[extremes][reduced]") {
  // Mass and inertia scaled together with the gains (the seed gains scale with them)
  // leave the motion unchanged: the same trajectory to round-off, the same strides, no
  // allocation warnings from absolute tolerances.
  const auto rn = reduced::simulate(test::load_shipped("case1_body_only"));
  const auto pn_scene = test::load_shipped("case3_legged_pulse");
  const auto pn = reduced::simulate(pn_scene);
  for (double mass : {1e-4, 1e-2, 1e2, 1e3}) {
    INFO("mass " << mass << " kg");
    const double f = mass / 1.5;
    char inertia[200];
    std::snprintf(inertia, sizeof inertia, "/body/inertia=[%.17g,%.17g,%.17g]", 0.0074 * f,
                  0.0106 * f, 0.0164 * f);
    char mass_set[64];
    std::snprintf(mass_set, sizeof mass_set, "/body/mass=%.17g", mass);
    const auto s = test::load_shipped("case1_body_only", {mass_set, inertia});
    const auto r = reduced::simulate(s);
    REQUIRE(r.status == reduced::RunStatus::kCompleted);
    CHECK(ex::all_finite(r));
    CHECK(r.strides.size() == rn.strides.size());
    CHECK((r.final_position - rn.final_position).norm() < 1e-9);
    CHECK(r.final_attitude.angularDistance(rn.final_attitude) < 1e-9);
    CHECK(r.warnings.empty());
    auto p_scene = pn_scene;  // explicit gains: scale them too
    p_scene.body.mass *= f;
    p_scene.body.inertia *= f;
    p_scene.controller.kp *= f;
    p_scene.controller.kd *= f;
    const auto p = reduced::simulate(p_scene);
    REQUIRE(p.status == reduced::RunStatus::kCompleted);
    CHECK(ex::all_finite(p));
    CHECK(p.strides.size() == pn.strides.size());
    CHECK((p.final_position - pn.final_position).norm() < 1e-8);
    CHECK(p.strides.back().peak_leg_force ==
          Approx(f * pn.strides.back().peak_leg_force).epsilon(1e-6));
    CHECK(p.warnings.empty());
  }
}

TEST_CASE("extreme: zero gravity in the reduced models lands and reports finite monitors",
          "[extremes][reduced]") {
  // Without gravity the flight drift had no scale (m g h = 0): |dE| / 0 was inf, and
  // `pronk simulate` failed with "non-finite number in output at
  // /monitors/max_flight_energy_drift". The drift is now relative to the flight's own
  // (kinetic) energy, which torque-free flight conserves.
  for (const char* name : {"case1_body_only", "case2_legged_impulse", "case3_legged_pulse"}) {
    INFO(name);
    const auto s = test::load_shipped(
        name, {"/gravity=0", "/initial/position=[0, 0, 1]", "/initial/velocity=[0.3, 0.1, -0.5]",
               "/initial/angular_velocity=[1, 2, 3]"});
    const auto r = reduced::simulate(s);
    INFO(to_string(r.status) << ": " << r.reason);
    CHECK(ex::all_finite(r));
    CHECK(r.status != reduced::RunStatus::kDiverged);
    REQUIRE_FALSE(r.strides.empty());
    // The CoM coasts at constant velocity: the first touchdown is at (z0 - l) / |vz|.
    CHECK(r.strides[0].t_touchdown == Approx((1.0 - s.legs.length) / 0.5).epsilon(1e-12));
    CHECK(r.strides[0].position.x() == Approx(0.3 * r.strides[0].t_touchdown).epsilon(1e-9));
    CHECK(r.monitors.max_flight_energy_drift > 0.0);  // measured, not zeroed
    CHECK(r.monitors.max_flight_energy_drift < 1e-8);
    const auto summary = io::run_summary_json(s, r, reduced::compute_metrics(s, r));
    CHECK(summary["monitors"]["max_flight_energy_drift"].get<double>() ==
          r.monitors.max_flight_energy_drift);
  }
}
