#include "sim/pseudorigid/body.hpp"

#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>

namespace pronk::pseudorigid {

bool construct_body(double mass, const Eigen::Matrix3d& inertia,
                    std::array<Eigen::Vector3d, 4>* local, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(mass > 0.0) || !std::isfinite(mass)) return fail("body mass must be > 0 and finite");
  if (!inertia.allFinite()) return fail("inertia tensor must be finite");
  const double scale = inertia.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return fail("inertia tensor must not be zero");
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
    return fail("inertia tensor must be symmetric (Ixy = Iyx, Ixz = Izx, Iyz = Izy)");
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (inertia + inertia.transpose()));
  const Eigen::Vector3d l = eig.eigenvalues();
  Eigen::Matrix3d v = eig.eigenvectors();
  if (v.determinant() < 0.0) v.col(2) *= -1.0;
  if (!(l.minCoeff() > 0.0)) return fail("principal moments must be > 0");
  const char* axis[3] = {"first", "second", "third"};
  for (int i = 0; i < 3; ++i) {
    const double others = l.sum() - l[i];
    if (l[i] > others * (1.0 + 1e-12)) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "principal moments %.6g, %.6g, %.6g violate the triangle inequality (the %s "
                    "exceeds the sum of the other two)",
                    l[0], l[1], l[2], axis[i]);
      return fail(buf);
    }
  }
  // Second moments along the principal axes.
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p[i] = 0.5 * (l.sum() - 2.0 * l[i]);
  if (p.minCoeff() <= 1e-9 * l.sum()) {
    return fail(
        "flat body (a principal moment equals the sum of the other two): four masses "
        "in a plane cannot be held rigid by six springs");
  }
  const Eigen::Vector3d abc = (p / mass).cwiseSqrt();
  const double s[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d r(s[i][0] * abc[0], s[i][1] * abc[1], s[i][2] * abc[2]);
    (*local)[i] = v * r;
  }
  if (error) error->clear();
  return true;
}

Eigen::Matrix3d point_mass_inertia(double mass, const std::array<Eigen::Vector3d, 4>& local) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& r : local) c += 0.25 * r;
  Eigen::Matrix3d i = Eigen::Matrix3d::Zero();
  for (const auto& r0 : local) {
    const Eigen::Vector3d r = r0 - c;
    i += 0.25 * mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  return i;
}

}  // namespace pronk::pseudorigid
