// Implementation of sim/math/rotation.hpp. All functions are allocation-free
// (fixed-size Eigen types only) and branch only on the gimbal-lock tests.
#include "sim/math/rotation.hpp"

#include <cmath>
#include <numbers>

namespace pronk::math {

namespace {

constexpr double kPi = std::numbers::pi;

/// |sin| or |cos| of the middle angle below which extraction is treated as
/// gimbal lock (coupled rotation folded into the first angle, third = 0).
constexpr double kLockTol = 1e-12;

/// |cos a2| below which euler123_rates returns its small-angle fallback.
constexpr double kRatesLockTol = 1e-9;

/// Quaternions whose (scaled) norm is below this are treated as degenerate.
constexpr double kMinQuatNorm = 1e-100;

/// Maps an atan2 result in [-pi, pi] to (-pi, pi] (atan2(-0, x<0) = -pi).
inline double wrap_pm_pi(double a) { return a <= -kPi ? a + 2.0 * kPi : a; }

/// R = Rx(a) Ry(b) Rz(c), written out.
Mat3 matrix123(double a, double b, double c) {
  const double sa = std::sin(a), ca = std::cos(a);
  const double sb = std::sin(b), cb = std::cos(b);
  const double sc = std::sin(c), cc = std::cos(c);
  Mat3 R;
  R << cb * cc, -cb * sc, sb,                                    //
      sa * sb * cc + ca * sc, ca * cc - sa * sb * sc, -sa * cb,  //
      sa * sc - ca * sb * cc, ca * sb * sc + sa * cc, ca * cb;
  return R;
}

/// R = Rz(a) Rx(b) Rz(c), written out.
Mat3 matrix313(double a, double b, double c) {
  const double sa = std::sin(a), ca = std::cos(a);
  const double sb = std::sin(b), cb = std::cos(b);
  const double sc = std::sin(c), cc = std::cos(c);
  Mat3 R;
  R << ca * cc - sa * cb * sc, -ca * sc - sa * cb * cc, sa * sb,  //
      sa * cc + ca * cb * sc, ca * cb * cc - sa * sc, -ca * sb,   //
      sb * sc, sb * cc, cb;
  return R;
}

/// Inverse of matrix123. The first angle comes from the last column, the third
/// from the first row of Rx(a)^T R = Ry(b) Rz(c) (so a and c stay mutually
/// consistent and the matrix is reproduced accurately even near the lock).
Vec3 extract123(const Mat3& R) {
  // |cos b| from the third column (R12 = -sa cb, R22 = ca cb).
  const double cb = std::hypot(R(1, 2), R(2, 2));
  const double b = std::atan2(R(0, 2), cb);  // in [-pi/2, pi/2] since cb >= 0
  if (!(cb >= kLockTol)) {
    // Lock: b = +pi/2 gives R = [.., ..; sin(a+c), cos(a+c)] in rows 1-2 cols
    // 0-1; b = -pi/2 gives sin(c-a), cos(c-a). With c = 0 this is a.
    const double s = R(0, 2) >= 0.0 ? 1.0 : -1.0;
    const double a = wrap_pm_pi(std::atan2(s * R(1, 0), R(1, 1)));
    return {a, b, 0.0};
  }
  const double a = std::atan2(-R(1, 2), R(2, 2));
  const double sa = std::sin(a), ca = std::cos(a);
  // Row 1 of Rx(a)^T R = (ca R1 + sa R2) = (sc, cc, 0).
  const double c = std::atan2(ca * R(1, 0) + sa * R(2, 0), ca * R(1, 1) + sa * R(2, 1));
  return {wrap_pm_pi(a), b, wrap_pm_pi(c)};
}

/// Inverse of matrix313; same strategy as extract123.
Vec3 extract313(const Mat3& R) {
  // sin b >= 0 from the third column (R02 = sa sb, R12 = -ca sb).
  const double sb = std::hypot(R(0, 2), R(1, 2));
  const double b = std::atan2(sb, R(2, 2));  // in [0, pi]
  if (!(sb >= kLockTol)) {
    // Lock: b = 0 gives R00 = cos(a+c), R10 = sin(a+c); b = pi gives
    // cos(a-c), sin(a-c). With c = 0 both are a.
    const double a = wrap_pm_pi(std::atan2(R(1, 0), R(0, 0)));
    return {a, b, 0.0};
  }
  const double a = std::atan2(R(0, 2), -R(1, 2));
  const double sa = std::sin(a), ca = std::cos(a);
  // Row 0 of Rz(a)^T R = (ca R0 + sa R1) = (cc, -sc, 0).
  const double c = std::atan2(-(ca * R(0, 1) + sa * R(1, 1)), ca * R(0, 0) + sa * R(1, 0));
  return {wrap_pm_pi(a), b, wrap_pm_pi(c)};
}

/// Unit quaternion of a rotation by `angle` about the coordinate axis `axis`.
inline Quat axis_quat(int axis, double angle) {
  const double h = 0.5 * angle;
  Quat q(std::cos(h), 0.0, 0.0, 0.0);
  q.vec()[axis] = std::sin(h);
  return q;
}

}  // namespace

Mat3 euler_to_matrix(const Vec3& angles, EulerSet set) {
  return set == EulerSet::k123 ? matrix123(angles[0], angles[1], angles[2])
                               : matrix313(angles[0], angles[1], angles[2]);
}

Quat euler_to_quat(const Vec3& angles, EulerSet set) {
  const int first = set == EulerSet::k123 ? 0 : 2;
  const int second = set == EulerSet::k123 ? 1 : 0;
  return axis_quat(first, angles[0]) * axis_quat(second, angles[1]) * axis_quat(2, angles[2]);
}

Vec3 matrix_to_euler(const Mat3& R, EulerSet set) {
  return set == EulerSet::k123 ? extract123(R) : extract313(R);
}

Vec3 quat_to_euler(const Quat& q, EulerSet set) {
  return matrix_to_euler(normalized_or_identity(q).toRotationMatrix(), set);
}

Eigen::Vector4d quat_derivative(const Quat& q, const Vec3& w_body) {
  // q ⊗ (0, w) = (-v·w, s w + v × w) with q = (s, v).
  const Vec3 v = q.vec();
  const Vec3 d = 0.5 * (q.w() * w_body + v.cross(w_body));
  return {-0.5 * v.dot(w_body), d.x(), d.y(), d.z()};
}

Vec3 euler123_rates(const Vec3& angles, const Vec3& w_body) {
  // w_body = E a_dot with (R = Rx(a1) Ry(a2) Rz(a3)):
  //   E = [ c2 c3   s3  0 ]
  //       [-c2 s3   c3  0 ]
  //       [ s2      0   1 ]
  const double s2 = std::sin(angles[1]), c2 = std::cos(angles[1]);
  const double s3 = std::sin(angles[2]), c3 = std::cos(angles[2]);
  if (std::abs(c2) < kRatesLockTol) return w_body;
  const double a1 = (c3 * w_body[0] - s3 * w_body[1]) / c2;
  const double a2 = s3 * w_body[0] + c3 * w_body[1];
  const double a3 = w_body[2] - s2 * a1;
  return {a1, a2, a3};
}

Vec3 euler_rates_to_world_omega(const Vec3& angles, const Vec3& rates, EulerSet set) {
  const double s1 = std::sin(angles[0]), c1 = std::cos(angles[0]);
  const double s2 = std::sin(angles[1]), c2 = std::cos(angles[1]);
  if (set == EulerSet::k123) {
    // x, Rx(a1) y, Rx(a1) Ry(a2) z.
    return rates[0] * Vec3::UnitX() + rates[1] * Vec3(0.0, c1, s1) +
           rates[2] * Vec3(s2, -s1 * c2, c1 * c2);
  }
  // z, Rz(a1) x, Rz(a1) Rx(a2) z.
  return rates[0] * Vec3::UnitZ() + rates[1] * Vec3(c1, s1, 0.0) +
         rates[2] * Vec3(s1 * s2, -c1 * s2, c2);
}

Vec3 euler_rates_to_body_omega(const Vec3& angles, const Vec3& rates, EulerSet set) {
  return euler_to_matrix(angles, set).transpose() * euler_rates_to_world_omega(angles, rates, set);
}

Vec3 quat_to_rotation_vector(const Quat& q) {
  // Shortest rotation: q and -q are the same attitude; use w >= 0.
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const double w = sign * q.w();
  const Vec3 v = sign * q.vec();
  const double n = v.norm();
  if (n == 0.0) return Vec3::Zero();
  if (n < 1e-8 * w) {
    // angle / n = 2 atan2(n, w) / n = (2 / w) (1 - (n/w)^2 / 3 + O((n/w)^4)).
    const double r = n / w;
    return (2.0 / w) * (1.0 - r * r / 3.0) * v;
  }
  const double angle = 2.0 * std::atan2(n, w);  // in [0, pi]
  return (angle / n) * v;
}

Quat normalized_or_identity(const Quat& q) {
  const Eigen::Vector4d c = q.coeffs();
  if (!c.allFinite()) return Quat::Identity();
  const double m = c.cwiseAbs().maxCoeff();  // scale first: no overflow/underflow
  if (!(m > 0.0)) return Quat::Identity();
  const Eigen::Vector4d u = c / m;
  const double n = u.norm();
  if (!(n * m > kMinQuatNorm)) return Quat::Identity();
  const Eigen::Vector4d r = u / n;
  return Quat(r[3], r[0], r[1], r[2]);  // coeffs() is (x, y, z, w)
}

}  // namespace pronk::math
