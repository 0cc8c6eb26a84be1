#include "sim/pseudorigid/rigid_body.hpp"

#include <cmath>

namespace pronk::pseudorigid {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

void rigid_quaternion_rate(const ode::Vec& y, int r, const Vector3d& omega, ode::Vec& dydt) {
  const double w = y[r], x = y[r + 1], yy = y[r + 2], z = y[r + 3];
  // 1/2 (0, omega) (w, v) = 1/2 (-omega . v, w omega + omega x v).
  dydt[r] = -0.5 * (omega.x() * x + omega.y() * yy + omega.z() * z);
  dydt[r + 1] = 0.5 * (w * omega.x() + omega.y() * z - omega.z() * yy);
  dydt[r + 2] = 0.5 * (w * omega.y() + omega.z() * x - omega.x() * z);
  dydt[r + 3] = 0.5 * (w * omega.z() + omega.x() * yy - omega.y() * x);
}

void principal_axes(const Matrix3d& inertia, Vector3d* moments, Matrix3d* axes) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> es(0.5 * (inertia + inertia.transpose()));
  *moments = es.eigenvalues();
  *axes = es.eigenvectors();
  if (axes->determinant() < 0.0) axes->col(2) *= -1.0;
}

void rigid_rotation_drift(const Body& b, double h, ode::Vec& y, int r) {
  const Vector3d& moments = b.principal_moments;
  const Matrix3d& axes = b.principal_axes;
  Quaterniond q = rigid_quaternion(y, r);
  const Vector3d L = y.segment<3>(r + 4);
  // Principal-frame angular momentum; each sub-flow turns the body about one principal axis
  // k by h_k L_k / I_k, which leaves L_k and the world L unchanged.
  Vector3d lp = axes.transpose() * (q.toRotationMatrix().transpose() * L);
  auto turn = [&](int k, double tau) {
    const double angle = tau * lp[k] / moments[k];
    const Eigen::AngleAxisd rot(angle, Vector3d::Unit(k));
    lp = rot.inverse() * lp;
    q = q * Quaterniond(Eigen::AngleAxisd(angle, axes.col(k)));
  };
  turn(0, 0.5 * h);
  turn(1, 0.5 * h);
  turn(2, h);
  turn(1, 0.5 * h);
  turn(0, 0.5 * h);
  q.normalize();
  y.segment<4>(r) << q.w(), q.x(), q.y(), q.z();
}

}  // namespace pronk::pseudorigid
