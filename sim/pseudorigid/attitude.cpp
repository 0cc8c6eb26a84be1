#include "sim/pseudorigid/attitude.hpp"

#include <cmath>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace pronk::pseudorigid {

namespace {

/// exp([w]x) by Rodrigues' formula (series for tiny angles).
Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& w) {
  const double t2 = w.squaredNorm();
  double a, b;  // sin(t)/t, (1 - cos t)/t^2
  if (t2 < 1e-8) {
    a = 1.0 - t2 / 6.0;
    b = 0.5 - t2 / 24.0;
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
  const Eigen::Matrix3d k = skew(w);
  return Eigen::Matrix3d::Identity() + a * k + b * (k * k);
}

bool initial_rotation(const Eigen::Matrix3d& m, const std::array<Eigen::Vector3d, 4>& local,
                      Eigen::Matrix3d* out);
bool newton_rotation(const Eigen::Matrix3d& m, Eigen::Matrix3d rot, Eigen::Matrix3d* r);

/// The rotation factor R of the polar decomposition M = R S (S symmetric), i.e.
/// the maximiser of tr(R^T M) over SO(3), by Newton's method on the rotation
/// group: with S = R^T M, tr((R exp[w])^T M) = tr S + w.a - w^T A w / 2 + O(w^3),
/// a = vee(S - S^T), A = tr(S) 1 - sym(S), so w = A^-1 a and R <- R exp[w]
/// (quadratic convergence). The start is `start` when given (and the
/// iteration converges from it), else the orthonormalised M S0^-1,
/// S0 = sum l_i l_i^T: exact for an undeformed body, off by O(strain) otherwise,
/// so two or three iterations reach round-off. Returns false when M is singular
/// or reflecting (det M <= 0 relative to its size) or the iteration does not
/// converge; the caller then falls back to the SVD.
bool polar_rotation(const Eigen::Matrix3d& m, const std::array<Eigen::Vector3d, 4>& local,
                    const Eigen::Matrix3d* start, Eigen::Matrix3d* r) {
  const double scale = m.norm();
  if (!(scale > 0.0) || !(m.determinant() > 1e-9 * scale * scale * scale)) return false;
  if (start != nullptr && newton_rotation(m, *start, r)) return true;
  Eigen::Matrix3d rot;
  return initial_rotation(m, local, &rot) && newton_rotation(m, rot, r);
}

/// Orthonormalised M S0^-1 (Gram-Schmidt, completed by the cross product).
bool initial_rotation(const Eigen::Matrix3d& m, const std::array<Eigen::Vector3d, 4>& local,
                      Eigen::Matrix3d* out) {
  Eigen::Matrix3d s0 = Eigen::Matrix3d::Zero();
  for (const auto& l : local) s0 += l * l.transpose();
  const Eigen::Matrix3d x = m * s0.inverse();
  Eigen::Matrix3d& rot = *out;
  const double n0 = x.col(0).norm();
  if (!(n0 > 0.0)) return false;
  rot.col(0) = x.col(0) / n0;
  const Eigen::Vector3d c1 = x.col(1) - rot.col(0).dot(x.col(1)) * rot.col(0);
  const double n1 = c1.norm();
  if (!(n1 > 0.0)) return false;
  rot.col(1) = c1 / n1;
  rot.col(2) = rot.col(0).cross(rot.col(1));
  return true;
}

/// Newton's iteration on SO(3) from `rot` (see polar_rotation).
bool newton_rotation(const Eigen::Matrix3d& m, Eigen::Matrix3d rot, Eigen::Matrix3d* r) {
  for (int it = 0; it < 12; ++it) {
    const Eigen::Matrix3d s = rot.transpose() * m;
    const Eigen::Vector3d a(s(2, 1) - s(1, 2), s(0, 2) - s(2, 0), s(1, 0) - s(0, 1));
    const Eigen::Matrix3d h = s.trace() * Eigen::Matrix3d::Identity() - 0.5 * (s + s.transpose());
    const Eigen::Vector3d w = h.inverse() * a;
    if (!w.allFinite()) return false;
    rot = rot * rotation_exp(w);
    // Quadratic convergence: the error left after a step of size |w| is O(|w|^2).
    if (w.norm() < 1e-9) {
      // A maximum, not another stationary point (R turned by pi about an axis):
      // there tr(S) 1 - S is positive definite (Sylvester's criterion).
      const Eigen::Matrix3d sf = rot.transpose() * m;
      const Eigen::Matrix3d hf =
          sf.trace() * Eigen::Matrix3d::Identity() - 0.5 * (sf + sf.transpose());
      if (!(hf(0, 0) > 0.0 && hf.topLeftCorner<2, 2>().determinant() > 0.0 &&
            hf.determinant() > 0.0)) {
        return false;
      }
      *r = rot;
      return true;
    }
  }
  return false;
}

}  // namespace

BodyFrame fit_attitude(const std::array<Eigen::Vector3d, 4>& x,
                       const std::array<Eigen::Vector3d, 4>& local, const Eigen::Matrix3d* start) {
  BodyFrame f;
  for (const auto& xi : x) f.com += 0.25 * xi;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) m += (x[i] - f.com) * local[i].transpose();
  if (!polar_rotation(m, local, start, &f.rotation)) {
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
