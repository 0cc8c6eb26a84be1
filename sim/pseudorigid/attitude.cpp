#include "sim/pseudorigid/attitude.hpp"

#include <cmath>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace pronk::pseudorigid {

namespace {

/// The rotation factor of the polar decomposition M = R S by Higham's scaled
/// Newton iteration X <- (g X + X^-T / g) / 2 (quadratic convergence, about
/// six 3x3 inverses; several times faster than a 3x3 Jacobi SVD). Returns
/// false when M is singular or reflecting (det M <= 0 relative to its size),
/// where the caller falls back to the SVD.
bool polar_rotation(const Eigen::Matrix3d& m, Eigen::Matrix3d* r) {
  const double scale = m.norm();
  if (!(scale > 0.0) || !(m.determinant() > 1e-9 * scale * scale * scale)) return false;
  Eigen::Matrix3d x = m;
  bool close = false;
  for (int it = 0; it < 30; ++it) {
    const Eigen::Matrix3d xit = x.inverse().transpose();
    const double g = close ? 1.0 : std::sqrt(xit.norm() / x.norm());
    const Eigen::Matrix3d next = 0.5 * (g * x + xit / g);
    const double change = (next - x).norm();
    x = next;
    if (close) break;                 // one more iteration after convergence set in
    if (change < 1e-9) close = true;  // quadratic: the next change is ~1e-18
  }
  if (!x.allFinite()) return false;
  *r = x;
  return true;
}

}  // namespace

BodyFrame fit_attitude(const std::array<Eigen::Vector3d, 4>& x,
                       const std::array<Eigen::Vector3d, 4>& local) {
  BodyFrame f;
  for (const auto& xi : x) f.com += 0.25 * xi;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) m += (x[i] - f.com) * local[i].transpose();
  if (!polar_rotation(m, &f.rotation)) {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) d(2, 2) = -1.0;
    f.rotation = svd.matrixU() * d * svd.matrixV().transpose();
  }
  f.stretch = f.rotation.transpose() * m;
  f.stretch = 0.5 * (f.stretch + f.stretch.transpose()).eval();
  return f;
}

Eigen::Vector3d fit_angular_velocity(const std::array<Eigen::Vector3d, 4>& x,
                                     const std::array<Eigen::Vector3d, 4>& v) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), vc = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    c += 0.25 * x[i];
    vc += 0.25 * v[i];
  }
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d r = x[i] - c;
    a += r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
    b += r.cross(v[i] - vc);
  }
  return a.fullPivLu().solve(b);
}

std::array<Eigen::Matrix3d, 4> attitude_derivative(const BodyFrame& frame,
                                                   const std::array<Eigen::Vector3d, 4>& local) {
  const Eigen::Matrix3d& s = frame.stretch;
  const Eigen::Matrix3d a = s.trace() * Eigen::Matrix3d::Identity() - s;
  const Eigen::Matrix3d a_inv = a.inverse();
  std::array<Eigen::Matrix3d, 4> out;
  for (int k = 0; k < 4; ++k) out[k] = a_inv * skew(local[k]) * frame.rotation.transpose();
  return out;
}

}  // namespace pronk::pseudorigid
