#include "sim/robot/feet_step_bound.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "sim/pseudorigid/attitude.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;

using Eigen::Matrix;
using Eigen::Vector3d;
using Matrix6d = Matrix<double, 6, 6>;
using Vector6d = Matrix<double, 6, 1>;

namespace {

/// The four-mass body: its 12 x 12 stiffness, the six body springs plus each leg spring (at
/// the hip, by its barycentric weights) and slot (at the foot: the hip's weights and the
/// turning normal's moment through the fitted attitude's derivative), about the rest shape.
double four_mass_omega(const scene::Scene& s, const RobotModel& m, double rest_scale,
                       const Vector3d& dir) {
  using Matrix12d = Matrix<double, 12, 12>;
  using Vector12d = Matrix<double, 12, 1>;
  const scene::PseudoRigid& p = s.pseudo_rigid;
  const pr::Body& body = m.mechanism.bodies[m.body];
  Matrix12d K = Matrix12d::Zero(), M = Matrix12d::Zero();
  for (int j = 0; j < 4; ++j) {
    M.block<3, 3>(3 * j, 3 * j) =
        m.mechanism.masses[static_cast<size_t>(body.first_mass + j)].mass *
        Eigen::Matrix3d::Identity();
  }
  auto index = [&](const pr::NodeRef& n) {
    return n.kind == pr::NodeRef::Kind::kMass ? n.index - body.first_mass : -1;
  };
  for (const pr::Connection& c : m.mechanism.connections) {
    const int a = index(c.a), b = index(c.b);
    if (a < 0 || a > 3 || b < 0 || b > 3 || !(c.stiffness > 0.0)) continue;
    const Vector3d u =
        (body.local[static_cast<size_t>(b)] - body.local[static_cast<size_t>(a)]).normalized();
    const Eigen::Matrix3d k = c.stiffness * u * u.transpose();
    K.block<3, 3>(3 * a, 3 * a) += k;
    K.block<3, 3>(3 * b, 3 * b) += k;
    K.block<3, 3>(3 * a, 3 * b) -= k;
    K.block<3, 3>(3 * b, 3 * a) -= k;
  }
  pr::BodyFrame rest;
  rest.stretch.setZero();
  for (const Vector3d& l : body.local) rest.stretch += l * l.transpose();
  const std::array<Eigen::Matrix3d, 4> omega = pr::attitude_derivative(rest, body.local);
  const std::array<Vector3d, 2> slot = slot_normals(dir, !p.hip_rotation);
  for (size_t i = 0; i < m.hip.size(); ++i) {
    const Eigen::Vector4d w = m.mechanism.ghost_points[m.hip_node[i].index].weights;
    const Vector3d r = rest_scale * m.rest_length[i] * dir;  // hip -> foot
    Vector12d leg;
    for (int j = 0; j < 4; ++j) leg.segment<3>(3 * j) = w[j] * dir;
    K += p.leg_stiffness * leg * leg.transpose();
    for (const Vector3d& n : slot) {
      if (n.squaredNorm() == 0.0) continue;
      Vector12d sl;
      for (int j = 0; j < 4; ++j) {
        sl.segment<3>(3 * j) = -w[j] * n + omega[static_cast<size_t>(j)].transpose() * n.cross(r);
      }
      K += p.internal_stiffness * sl * sl.transpose();
    }
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix12d> eig(K, M, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
}

}  // namespace

std::array<Vector3d, 2> slot_normals(const Vector3d& dir, bool locked) {
  Vector3d n1 = dir.cross(Vector3d::UnitX());
  if (!locked) {
    return {n1.norm() > 1e-6 ? Vector3d(n1.normalized()) : Vector3d::Zero(), Vector3d::Zero()};
  }
  if (n1.norm() <= 1e-6) n1 = dir.cross(Vector3d::UnitY());
  n1.normalize();
  return {n1, dir.cross(n1).normalized()};
}

double quasi_static_omega(const scene::Scene& s, const RobotModel& m, double rest_scale,
                          const Vector3d& dir) {
  if (!m.mechanism.bodies[m.body].rigid) return four_mass_omega(s, m, rest_scale, dir);
  const scene::PseudoRigid& p = s.pseudo_rigid;
  Matrix6d K = Matrix6d::Zero();
  auto add = [&](double k, const Vector3d& u, const Vector3d& at) {
    Vector6d j;
    j << u, at.cross(u);
    K += k * j * j.transpose();
  };
  const std::array<Vector3d, 2> slot = slot_normals(dir, !p.hip_rotation);
  for (size_t i = 0; i < m.hip.size(); ++i) {
    const Vector3d foot = m.hip[i] + rest_scale * m.rest_length[i] * dir;
    add(p.leg_stiffness, -dir, m.hip[i]);
    for (const Vector3d& n : slot) {
      if (n.squaredNorm() > 0.0) add(p.internal_stiffness, n, foot);
    }
  }
  Matrix6d M = Matrix6d::Zero();
  M.topLeftCorner<3, 3>() = s.body.mass * Eigen::Matrix3d::Identity();
  M.bottomRightCorner<3, 3>() = s.body.inertia;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> eig(K, M, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
}

double quasi_static_omega(const scene::Scene& s, const RobotModel& m) {
  if (!m.quasi_static_feet) return 0.0;
  const double a = s.pseudo_rigid.hip_rotation ? std::tan(s.pseudo_rigid.max_leg_angle) : 0.0;
  const bool level = s.pseudo_rigid.hip_rotation && s.pseudo_rigid.level_feet;
  double w = 0.0;
  for (double scale : {0.75, 1.0, 1.25}) {
    if (!level && scale != 1.0) continue;
    for (double fore : {-a, 0.0, a}) {
      for (double side : {-a, 0.0, a}) {
        const Vector3d dir = Vector3d(fore, side, -1.0).normalized();
        w = std::max(w, quasi_static_omega(s, m, scale, dir));
      }
    }
  }
  return w;
}

}  // namespace pronk::robot
