// Newton-Euler rigid body with massless legs: state layout, flight/stance
// right-hand side, instantaneous impulses. Two attitude formulations: the exact
// unit quaternion (default) and the seed's small-angle 1-2-3 Euler formulation.
#pragma once

#include <Eigen/Core>

#include "sim/control/body_state.hpp"
#include "sim/math/rotation.hpp"
#include "sim/ode/ode_system.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using math::Quat;
using ode::Vec;

/// State vector layout. Quaternion: [r(3) v(3) q(w,x,y,z) w_body(3)] = 13;
/// small-angle: [r(3) v(3) theta123(3) w_body(3)] = 12. Optionally followed by
/// 3 quadrature states: the world-frame linear impulse delivered by the legs [N s].
struct Layout {
  bool quaternion = true;
  bool impulse_quadrature = false;
  int attitude_size() const { return quaternion ? 4 : 3; }
  int omega_index() const { return 6 + attitude_size(); }
  int base_size() const { return omega_index() + 3; }
  int quadrature_index() const { return base_size(); }
  int size() const { return base_size() + (impulse_quadrature ? 3 : 0); }
};

using control::BodyState;

/// Const physical model of the reduced body, shared by runs.
struct RigidBodyModel {
  RigidBodyModel(const scene::Scene& scene, bool impulse_quadrature);
  Layout layout;
  double mass;           ///< [kg]
  Mat3 inertia;          ///< body frame [kg m^2]
  Mat3 inertia_inverse;  ///< [1/(kg m^2)]
  Vec3 gravity;          ///< world [m/s^2]

  BodyState decode(const Vec& y) const;
  void encode(const BodyState& s, Vec& y) const;
  /// Writes the initial state of the scene.
  void initial_state(const scene::Scene& scene, Vec& y) const;
  /// Applies an instantaneous linear impulse (world) [N s] and angular impulse (body) [N m s].
  void apply_impulse(Vec& y, const Vec3& P_world, const Vec3& H_body) const;
  /// Total mechanical energy (kinetic + rotational + gravitational, z = 0 datum) [J].
  double energy(const Vec& y) const;
  /// Renormalises the quaternion (quaternion layout only).
  void normalize(Vec& y) const;
};

/// f(t, y) with a constant body-frame leg force and moment (zero in flight).
class RigidBodyRhs final : public ode::OdeSystem {
 public:
  explicit RigidBodyRhs(const RigidBodyModel& model) : model_(model) {}
  int dimension() const override { return model_.layout.size(); }
  void rhs(double t, const Vec& y, Vec& dydt) const override;
  /// Leg force [N] and moment about the CoM [N m], both body frame.
  void set_leg_load(const Vec3& force_body, const Vec3& moment_body) {
    force_body_ = force_body;
    moment_body_ = moment_body;
  }

 private:
  const RigidBodyModel& model_;
  Vec3 force_body_ = Vec3::Zero();
  Vec3 moment_body_ = Vec3::Zero();
};

}  // namespace pronk::reduced
