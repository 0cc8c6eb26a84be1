#include "sim/robot/feet_step_bound.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace pronk::robot {

using Eigen::Matrix;
using Eigen::Vector3d;
using Matrix6d = Matrix<double, 6, 6>;
using Vector6d = Matrix<double, 6, 1>;

double quasi_static_omega(const scene::Scene& s, const RobotModel& m, double rest_scale,
                          const Vector3d& dir) {
  const scene::PseudoRigid& p = s.pseudo_rigid;
  Matrix6d K = Matrix6d::Zero();
  auto add = [&](double k, const Vector3d& u, const Vector3d& at) {
    Vector6d j;
    j << u, at.cross(u);
    K += k * j * j.transpose();
  };
  const Vector3d slot = dir.cross(Vector3d::UnitX());
  for (size_t i = 0; i < m.hip.size(); ++i) {
    const Vector3d foot = m.hip[i] + rest_scale * m.rest_length[i] * dir;
    add(p.leg_stiffness, -dir, m.hip[i]);
    if (slot.norm() > 1e-6) add(p.internal_stiffness, slot.normalized(), foot);
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
