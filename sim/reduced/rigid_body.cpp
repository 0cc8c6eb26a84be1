#include "sim/reduced/rigid_body.hpp"

namespace pronk::reduced {

RigidBodyModel::RigidBodyModel(const scene::Scene& scene, bool impulse_quadrature)
    : mass(scene.body.mass),
      inertia(scene.body.inertia),
      inertia_inverse(scene.body.inertia.inverse()),
      gravity(0.0, 0.0, -scene.gravity) {
  layout.quaternion = scene.attitude == scene::AttitudeFormulation::kQuaternion;
  layout.impulse_quadrature = impulse_quadrature;
}

BodyState RigidBodyModel::decode(const Vec& y) const {
  BodyState s;
  s.position = y.segment<3>(0);
  s.velocity = y.segment<3>(3);
  if (layout.quaternion) {
    s.attitude = math::normalized_or_identity(Quat(y[6], y[7], y[8], y[9]));
    s.rotation = s.attitude.toRotationMatrix();
    s.euler123 = math::matrix_to_euler(s.rotation, math::EulerSet::k123);
  } else {
    s.euler123 = y.segment<3>(6);
    s.attitude = math::euler_to_quat(s.euler123, math::EulerSet::k123);
    s.rotation = s.attitude.toRotationMatrix();
  }
  s.omega = y.segment<3>(layout.omega_index());
  return s;
}

void RigidBodyModel::encode(const BodyState& s, Vec& y) const {
  y.segment<3>(0) = s.position;
  y.segment<3>(3) = s.velocity;
  if (layout.quaternion) {
    y[6] = s.attitude.w();
    y[7] = s.attitude.x();
    y[8] = s.attitude.y();
    y[9] = s.attitude.z();
  } else {
    y.segment<3>(6) = s.euler123;
  }
  y.segment<3>(layout.omega_index()) = s.omega;
}

void RigidBodyModel::initial_state(const scene::Scene& scene, Vec& y) const {
  y.setZero(layout.size());
  BodyState s;
  s.position = scene.initial.position;
  s.velocity = scene.initial.velocity;
  s.attitude = scene.initial.attitude.normalized();
  s.euler123 = math::quat_to_euler(s.attitude, math::EulerSet::k123);
  s.omega = scene.initial.angular_velocity;
  encode(s, y);
}

void RigidBodyModel::apply_impulse(Vec& y, const Vec3& P_world, const Vec3& H_body) const {
  y.segment<3>(3) += P_world / mass;
  y.segment<3>(layout.omega_index()) += inertia_inverse * H_body;
}

double RigidBodyModel::energy(const Vec& y) const {
  const Vec3 v = y.segment<3>(3);
  const Vec3 w = y.segment<3>(layout.omega_index());
  return 0.5 * mass * v.squaredNorm() + 0.5 * w.dot(inertia * w) -
         mass * gravity.dot(y.segment<3>(0));
}

void RigidBodyModel::normalize(Vec& y) const {
  if (!layout.quaternion) return;
  Quat q = math::normalized_or_identity(Quat(y[6], y[7], y[8], y[9]));
  y[6] = q.w();
  y[7] = q.x();
  y[8] = q.y();
  y[9] = q.z();
}

void RigidBodyRhs::rhs(double /*t*/, const Vec& y, Vec& dydt) const {
  const Layout& L = model_.layout;
  const int wi = L.omega_index();
  const Vec3 w = y.segment<3>(wi);
  dydt.segment<3>(0) = y.segment<3>(3);
  Vec3 force_world = Vec3::Zero();
  const bool loaded = !force_body_.isZero(0.0) || !moment_body_.isZero(0.0);
  if (L.quaternion) {
    // dq/dt = 1/2 q (x) (0, w); the quaternion is used as integrated (its norm
    // stays 1 to solver tolerance and is renormalised at every event restart).
    const double qw = y[6], qx = y[7], qy = y[8], qz = y[9];
    dydt[6] = 0.5 * (-qx * w.x() - qy * w.y() - qz * w.z());
    dydt[7] = 0.5 * (qw * w.x() + qy * w.z() - qz * w.y());
    dydt[8] = 0.5 * (qw * w.y() + qz * w.x() - qx * w.z());
    dydt[9] = 0.5 * (qw * w.z() + qx * w.y() - qy * w.x());
    if (loaded) {
      force_world = Quat(qw, qx, qy, qz).normalized().toRotationMatrix() * force_body_;
    }
  } else {
    // Seed (A.1): Euler angle states integrated as body rates (small angles only).
    dydt.segment<3>(6) = w;
    if (loaded) {
      force_world = math::euler_to_matrix(y.segment<3>(6), math::EulerSet::k123) * force_body_;
    }
  }
  dydt.segment<3>(3) = model_.gravity + force_world / model_.mass;
  // Euler's equations with the full inertia tensor: I dw/dt = M - w x (I w).
  dydt.segment<3>(wi) = model_.inertia_inverse * (moment_body_ - w.cross(model_.inertia * w));
  if (L.impulse_quadrature) dydt.segment<3>(L.quadrature_index()) = force_world;
}

}  // namespace pronk::reduced
