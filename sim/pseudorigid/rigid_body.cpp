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

void rigid_rotation_drift(const Body& b, double h, ode::Vec& y, int r, const Matrix3d* rotation) {
  const Vector3d& moments = b.principal_moments;
  const Matrix3d& axes = b.principal_axes;
  Quaterniond q = rigid_quaternion(y, r);
  const Vector3d L = y.segment<3>(r + 4);
  // Principal-frame angular momentum; each sub-flow turns the body about one principal axis
  // k by h_k L_k / I_k, which leaves L_k and the world L unchanged.
  const Matrix3d rot = rotation != nullptr ? *rotation : q.toRotationMatrix();
  Vector3d lp = axes.transpose() * (rot.transpose() * L);
  // One sine and cosine per sub-flow, of the half angle: the quaternion's, and the turn of lp
  // from them by the double-angle formulas.
  auto turn = [&](int k, double tau) {
    const double half = 0.5 * tau * lp[k] / moments[k];
    if (half == 0.0) return;  // no turn (no momentum about k): identity, bit for bit
    const double s = std::sin(half), c = std::cos(half);
    const double sa = 2.0 * s * c, ca = (c - s) * (c + s);
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double li = lp[i], lj = lp[j];
    lp[i] = ca * li + sa * lj;  // lp in the turned body frame: R_k(angle)^T lp
    lp[j] = ca * lj - sa * li;
    const Vector3d a = s * axes.col(k);
    q = q * Quaterniond(c, a.x(), a.y(), a.z());
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
