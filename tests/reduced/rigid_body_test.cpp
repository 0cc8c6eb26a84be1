// Torque-free rigid body against conservation laws and the analytic precession
// of an axisymmetric body (Ridgely 2001, §4.4.1), and the two attitude formulations.
#include <catch2/catch.hpp>

#include <cmath>

#include "sim/math/rotation.hpp"
#include "sim/ode/solver.hpp"
#include "sim/reduced/rigid_body.hpp"

using namespace pronk;
using Eigen::Vector3d;

namespace {

// A free body in zero gravity with the given inertia and initial state.
scene::Scene free_body(const Vector3d& I, const math::Quat& q0, const Vector3d& w_body,
                       scene::AttitudeFormulation formulation) {
  scene::Scene s;
  s.gravity = 0.0;
  s.attitude = formulation;
  s.body.inertia = I.asDiagonal();
  s.initial.position = Vector3d(0, 0, 1);
  s.initial.attitude = q0;
  s.initial.angular_velocity = w_body;
  return s;
}

struct Integrated {
  reduced::BodyState state;
  double t;
};

// Integrates to t_end with DOPRI5 at the given tolerance.
Integrated integrate_free(const reduced::RigidBodyModel& model, const scene::Scene& s, double t_end,
                          double tol) {
  reduced::RigidBodyRhs rhs(model);
  ode::SolverOptions o;
  o.rtol = o.atol = tol;
  o.h_max = 1.0;
  auto stepper = ode::make_stepper(o, model.layout.size());
  ode::Vec y;
  model.initial_state(s, y);
  stepper->reset(rhs, 0.0, y);
  const auto r = ode::integrate(rhs, *stepper, t_end, {}, o);
  REQUIRE(r.reason == ode::StopReason::kReachedEnd);
  return {model.decode(stepper->y()), r.t};
}

Vector3d world_momentum(const reduced::RigidBodyModel& m, const reduced::BodyState& s) {
  return s.rotation * (m.inertia * s.omega);
}
double rotational_energy(const reduced::RigidBodyModel& m, const reduced::BodyState& s) {
  return 0.5 * s.omega.dot(m.inertia * s.omega);
}

}  // namespace

TEST_CASE("torque-free body conserves energy and angular momentum over 100 s", "[rigid_body]") {
  const Vector3d I(0.0074, 0.0106, 0.0164);
  const math::Quat q0 = math::euler_to_quat(Vector3d(0.3, -0.2, 1.0), math::EulerSet::k123);
  const Vector3d w0(2.0, 0.3, 1.0);  // near the unstable intermediate axis: a hard case
  const auto s = free_body(I, q0, w0, scene::AttitudeFormulation::kQuaternion);
  const reduced::RigidBodyModel model(s, false);
  reduced::BodyState start;
  start.rotation = q0.toRotationMatrix();
  start.omega = w0;
  const Vector3d L0 = world_momentum(model, start);
  const double E0 = rotational_energy(model, start);
  const auto end = integrate_free(model, s, 100.0, 1e-12);
  CHECK(std::abs(rotational_energy(model, end.state) - E0) / E0 < 1e-9);
  CHECK((world_momentum(model, end.state) - L0).norm() / L0.norm() < 1e-9);
}

TEST_CASE("axisymmetric free body precesses at the analytic rate (case 10)", "[rigid_body]") {
  // Ixx = Iyy = 1, Izz = 0.25; 3-1-3 angles psi = 180 deg, theta = 30 deg, phi = 0;
  // spin rate phi_dot = 1 rad/s; precession psi_dot = Izz phi_dot / ((Ixx - Izz) cos theta).
  const double Ixx = 1.0, Izz = 0.25, theta = 30.0 * M_PI / 180.0, phi_dot = 1.0;
  const double psi_dot = Izz * phi_dot / ((Ixx - Izz) * std::cos(theta));
  REQUIRE(psi_dot == Approx(0.3849).epsilon(1e-3));
  const Vector3d angles0(M_PI, theta, 0.0);
  const math::Quat q0 = math::euler_to_quat(angles0, math::EulerSet::k313);
  const Vector3d w_body = math::euler_rates_to_body_omega(angles0, Vector3d(psi_dot, 0.0, phi_dot),
                                                          math::EulerSet::k313);
  const Vector3d w_world = q0 * w_body;
  // The seed's omega_0 = (0, 0.5, 1.251) rad/s in the world frame.
  CHECK(w_world.x() == Approx(0.0).margin(1e-12));
  CHECK(w_world.y() == Approx(0.5).epsilon(1e-9));
  CHECK(w_world.z() == Approx(1.2509).epsilon(1e-3));

  const auto s =
      free_body(Vector3d(Ixx, Ixx, Izz), q0, w_body, scene::AttitudeFormulation::kQuaternion);
  const reduced::RigidBodyModel model(s, false);
  for (double t : {1.0, 5.0, 20.0}) {
    const auto end = integrate_free(model, s, t, 1e-12);
    const Vector3d a = math::quat_to_euler(end.state.attitude, math::EulerSet::k313);
    // theta stays constant; psi advances at psi_dot; phi at phi_dot.
    CHECK(a.y() == Approx(theta).margin(1e-9));
    const double psi_expected = std::remainder(M_PI + psi_dot * t, 2 * M_PI);
    CHECK(std::remainder(a.x() - psi_expected, 2 * M_PI) == Approx(0.0).margin(1e-8));
    CHECK(std::remainder(a.z() - phi_dot * t, 2 * M_PI) == Approx(0.0).margin(1e-8));
  }
  // Loose tolerances drift, tight ones coincide.
  const auto loose = integrate_free(model, s, 20.0, 1e-4);
  const auto tight = integrate_free(model, s, 20.0, 1e-12);
  const double drift_loose = loose.state.attitude.angularDistance(tight.state.attitude);
  CHECK(drift_loose > 1e-7);
  CHECK(drift_loose < 1e-1);
}

TEST_CASE("small-angle formulation: right for small angles, wrong for large ones", "[rigid_body]") {
  const Vector3d I(0.0074, 0.0106, 0.0164);
  SECTION("1 degree: the formulations agree") {
    const Vector3d angles(1.0 * M_PI / 180, 0.0, 0.0);
    const math::Quat q0 = math::euler_to_quat(angles, math::EulerSet::k123);
    const Vector3d w0(0.02, -0.03, 0.01);
    const auto se = free_body(I, q0, w0, scene::AttitudeFormulation::kQuaternion);
    const auto ss = free_body(I, q0, w0, scene::AttitudeFormulation::kSmallAngleEuler123);
    const reduced::RigidBodyModel me(se, false), ms(ss, false);
    const auto e = integrate_free(me, se, 0.4, 1e-12);
    const auto sm = integrate_free(ms, ss, 0.4, 1e-12);
    // Both leave the body within ~1 deg; their difference is second order (< 1e-4 rad).
    CHECK(e.state.attitude.angularDistance(sm.state.attitude) < 1e-4);
  }
  SECTION("60 degree yaw with roll: they differ, and only the exact one conserves momentum") {
    const Vector3d angles(0.2, 0.0, 0.0);
    const math::Quat q0 = math::euler_to_quat(angles, math::EulerSet::k123);
    const Vector3d w0(0.5, 0.4, 60.0 * M_PI / 180.0 / 0.4);  // ~60 deg of yaw in one 0.4 s flight
    const auto se = free_body(I, q0, w0, scene::AttitudeFormulation::kQuaternion);
    const auto ss = free_body(I, q0, w0, scene::AttitudeFormulation::kSmallAngleEuler123);
    const reduced::RigidBodyModel me(se, false), ms(ss, false);
    reduced::BodyState start;
    start.rotation = q0.toRotationMatrix();
    start.omega = w0;
    const Vector3d L0 = world_momentum(me, start);
    const auto e = integrate_free(me, se, 0.4, 1e-12);
    const auto sm = integrate_free(ms, ss, 0.4, 1e-12);
    CHECK(e.state.attitude.angularDistance(sm.state.attitude) > 1.0 * M_PI / 180);
    CHECK((world_momentum(me, e.state) - L0).norm() / L0.norm() < 1e-10);
    CHECK((world_momentum(ms, sm.state) - L0).norm() / L0.norm() > 1e-2);
  }
}
