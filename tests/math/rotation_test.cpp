// Tests of sim/math/rotation.hpp against independent references: Eigen's
// AngleAxis products, finite differences and hand-derived closed forms.
#include "sim/math/rotation.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

using namespace pronk::math;

namespace {

constexpr double kPi = std::numbers::pi;

/// Reference matrix: explicit product of elementary rotations built with AngleAxis.
Mat3 ref_matrix(const Vec3& a, EulerSet set) {
  using AA = Eigen::AngleAxisd;
  if (set == EulerSet::k123) {
    return (AA(a[0], Vec3::UnitX()) * AA(a[1], Vec3::UnitY()) * AA(a[2], Vec3::UnitZ()))
        .toRotationMatrix();
  }
  return (AA(a[0], Vec3::UnitZ()) * AA(a[1], Vec3::UnitX()) * AA(a[2], Vec3::UnitZ()))
      .toRotationMatrix();
}

/// Angle difference wrapped into (-pi, pi].
double wrap(double d) { return std::remainder(d, 2.0 * kPi); }

double max_abs(const Mat3& m) { return m.cwiseAbs().maxCoeff(); }

bool in_range(const Vec3& a, EulerSet set) {
  const bool ends = a[0] > -kPi && a[0] <= kPi && a[2] > -kPi && a[2] <= kPi;
  if (set == EulerSet::k123) return ends && a[1] >= -kPi / 2 && a[1] <= kPi / 2;
  return ends && a[1] >= 0.0 && a[1] <= kPi;
}

/// Random angles inside the documented ranges, middle angle at least `margin`
/// [rad] away from the singular values.
Vec3 random_angles(std::mt19937_64& rng, EulerSet set, double margin) {
  std::uniform_real_distribution<double> u(-kPi, kPi);
  std::uniform_real_distribution<double> mid123(-kPi / 2 + margin, kPi / 2 - margin);
  std::uniform_real_distribution<double> mid313(margin, kPi - margin);
  const double a1 = u(rng);
  const double a2 = set == EulerSet::k123 ? mid123(rng) : mid313(rng);
  const double a3 = u(rng);
  return {a1, a2, a3};
}

/// Body-frame rotation by rotation vector phi [rad].
Mat3 exp_so3(const Vec3& phi) {
  const double n = phi.norm();
  if (n == 0.0) return Mat3::Identity();
  return Eigen::AngleAxisd(n, phi / n).toRotationMatrix();
}

}  // namespace

TEST_CASE("Euler round trips away from gimbal lock", "[rotation]") {
  for (EulerSet set : {EulerSet::k123, EulerSet::k313}) {
    std::mt19937_64 rng(20240611);
    double worst_angle = 0.0, worst_matrix = 0.0, worst_quat = 0.0;
    for (int i = 0; i < 10000; ++i) {
      const Vec3 a = random_angles(rng, set, 0.05);
      const Mat3 R = euler_to_matrix(a, set);
      const Vec3 back = matrix_to_euler(R, set);
      REQUIRE(back.allFinite());
      REQUIRE(in_range(back, set));
      worst_angle = std::max(worst_angle, (back - a).cwiseAbs().maxCoeff());
      worst_matrix = std::max(worst_matrix, max_abs(euler_to_matrix(back, set) - R));

      const Quat q = euler_to_quat(a, set);
      REQUIRE(std::abs(q.norm() - 1.0) < 1e-14);
      worst_quat = std::max(worst_quat, max_abs(q.toRotationMatrix() - R));
      const Vec3 from_q = quat_to_euler(q, set);
      worst_angle = std::max(worst_angle, (from_q - a).cwiseAbs().maxCoeff());
      // -q is the same attitude.
      const Quat mq(-q.w(), -q.x(), -q.y(), -q.z());
      worst_angle = std::max(worst_angle, (quat_to_euler(mq, set) - a).cwiseAbs().maxCoeff());
    }
    CHECK(worst_angle < 1e-10);
    CHECK(worst_matrix < 1e-12);
    CHECK(worst_quat < 1e-12);
  }
}

TEST_CASE("euler_to_matrix equals the product of elementary rotations", "[rotation]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(-10.0, 10.0);  // any angles, not just ranges
  for (EulerSet set : {EulerSet::k123, EulerSet::k313}) {
    for (int i = 0; i < 1000; ++i) {
      const Vec3 a(any(rng), any(rng), any(rng));
      CHECK(max_abs(euler_to_matrix(a, set) - ref_matrix(a, set)) < 1e-14);
      CHECK(max_abs(euler_to_quat(a, set).toRotationMatrix() - ref_matrix(a, set)) < 1e-14);
    }
  }
  // A hand-checked case: Rx(90°) maps body y to world z.
  const Mat3 Rx = euler_to_matrix(Vec3(kPi / 2, 0, 0), EulerSet::k123);
  CHECK((Rx * Vec3::UnitY() - Vec3::UnitZ()).norm() < 1e-15);
  // Rz(90°) in 3-1-3 maps body x to world y.
  const Mat3 Rz = euler_to_matrix(Vec3(kPi / 2, 0, 0), EulerSet::k313);
  CHECK((Rz * Vec3::UnitX() - Vec3::UnitY()).norm() < 1e-15);
}

TEST_CASE("Gimbal lock: third angle 0, rotation in the first, matrix reproduced", "[rotation]") {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  struct Lock {
    EulerSet set;
    double a2;
    double sign;  // first angle is a1 + sign * a3
  };
  const Lock locks[] = {{EulerSet::k123, kPi / 2, 1.0},
                        {EulerSet::k123, -kPi / 2, -1.0},
                        {EulerSet::k313, 0.0, 1.0},
                        {EulerSet::k313, kPi, -1.0}};
  for (const Lock& l : locks) {
    for (int i = 0; i < 1000; ++i) {
      const Vec3 a(u(rng), l.a2, u(rng));
      const Mat3 R = euler_to_matrix(a, l.set);
      const Vec3 e = matrix_to_euler(R, l.set);
      REQUIRE(e.allFinite());
      REQUIRE(in_range(e, l.set));
      CHECK(e[2] == 0.0);
      CHECK(std::abs(e[1] - l.a2) < 1e-15);
      CHECK(std::abs(wrap(e[0] - (a[0] + l.sign * a[2]))) < 1e-12);
      CHECK(max_abs(euler_to_matrix(e, l.set) - R) < 1e-12);
    }
  }
  // Exact lock matrices built by hand (no rounding in the singular entries).
  Mat3 R;
  R << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // Ry(+90°)
  Vec3 e = matrix_to_euler(R, EulerSet::k123);
  CHECK(e.isApprox(Vec3(0, kPi / 2, 0)));
  R << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // Rx(90°) Ry(90°)
  e = matrix_to_euler(R, EulerSet::k123);
  CHECK(std::abs(e[0] - kPi / 2) < 1e-15);
  CHECK(e[2] == 0.0);
  CHECK(max_abs(euler_to_matrix(e, EulerSet::k123) - R) < 1e-15);
}

TEST_CASE("Near gimbal lock: finite angles reproducing the matrix", "[rotation]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  const double offsets[] = {1e-16, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-6, 1e-4};
  for (double d : offsets) {
    for (int i = 0; i < 200; ++i) {
      const Vec3 a123[] = {{u(rng), kPi / 2 - d, u(rng)}, {u(rng), -kPi / 2 + d, u(rng)}};
      const Vec3 a313[] = {{u(rng), d, u(rng)}, {u(rng), kPi - d, u(rng)}};
      for (EulerSet set : {EulerSet::k123, EulerSet::k313}) {
        for (const Vec3& a : set == EulerSet::k123 ? a123 : a313) {
          // Matrices from three sources: the closed form (entries with
          // relative accuracy), and the AngleAxis product and the quaternion
          // (entries with absolute rounding errors, the harder case).
          const Mat3 sources[] = {euler_to_matrix(a, set), ref_matrix(a, set),
                                  euler_to_quat(a, set).toRotationMatrix()};
          for (const Mat3& R : sources) {
            const Vec3 e = matrix_to_euler(R, set);
            REQUIRE(e.allFinite());
            REQUIRE(in_range(e, set));
            CHECK(max_abs(euler_to_matrix(e, set) - R) < 1e-9);
          }
        }
      }
    }
  }
}

TEST_CASE("matrix_to_euler is robust to rounding and keeps angles within (-pi, pi)", "[rotation]") {
  // Entries slightly outside [-1, 1].
  Mat3 R = Mat3::Identity() * (1.0 + 4e-16);
  for (EulerSet set : {EulerSet::k123, EulerSet::k313}) {
    CHECK(matrix_to_euler(R, set).allFinite());
    CHECK(matrix_to_euler(Mat3::Zero(), set).allFinite());
    Mat3 S;
    S << 0, 0, 1.0000000000000004, 0, 1, 0, -1.0000000000000004, 0, 0;
    CHECK(matrix_to_euler(S, set).allFinite());
  }
  // diag(1, -1, -1) = Rx(pi): with signed zeros atan2 would give -pi.
  R << 1, 0, 0, 0, -1, -0.0, 0, 0.0, -1;
  Vec3 e = matrix_to_euler(R, EulerSet::k123);
  CHECK(e[0] == kPi);
  CHECK(in_range(e, EulerSet::k123));
  // Rz(pi) as 3-1-3 (lock at a2 = 0): first angle pi, not -pi.
  R << -1, 0.0, 0, -0.0, -1, 0, 0, 0, 1;
  e = matrix_to_euler(R, EulerSet::k313);
  CHECK(e[0] == kPi);
  CHECK(e[2] == 0.0);
  // Rx(pi) in 3-1-3: psi = 0 or pi, theta = pi, third 0.
  R << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  e = matrix_to_euler(R, EulerSet::k313);
  CHECK(in_range(e, EulerSet::k313));
  CHECK(max_abs(euler_to_matrix(e, EulerSet::k313) - R) < 1e-15);
}

TEST_CASE("quat_derivative matches a central difference of q exp(w dt / 2)", "[rotation]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  const double dt = 1e-5;
  for (int i = 0; i < 1000; ++i) {
    const Quat q = Quat(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng))).normalized();
    const Vec3 w(u(rng), u(rng), u(rng));
    auto step = [&](double h) {
      const Vec3 half = 0.5 * h * w;
      const double n = half.norm();
      const Vec3 v = n > 0 ? Vec3(half * (std::sin(n) / n)) : Vec3::Zero();
      const Quat e(std::cos(n), v.x(), v.y(), v.z());
      return q * e;
    };
    const Quat qp = step(dt), qm = step(-dt);
    const Eigen::Vector4d fd((qp.w() - qm.w()) / (2 * dt), (qp.x() - qm.x()) / (2 * dt),
                             (qp.y() - qm.y()) / (2 * dt), (qp.z() - qm.z()) / (2 * dt));
    const Eigen::Vector4d d = quat_derivative(q, w);
    CHECK((d - fd).norm() <= 1e-8 * d.norm());
    // A unit quaternion's derivative is orthogonal to it.
    CHECK(std::abs(d.dot(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()))) < 1e-14);
  }
}

TEST_CASE("euler123_rates matches finite differences of the extracted angles", "[rotation]") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const double dt = 1e-6;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 a = random_angles(rng, EulerSet::k123, 0.1);
    const Vec3 w(u(rng), u(rng), u(rng));
    const Mat3 R = euler_to_matrix(a, EulerSet::k123);
    // Body rates: R(t + h) = R(t) exp([w] h).
    const Vec3 ap = matrix_to_euler(R * exp_so3(w * dt), EulerSet::k123);
    const Vec3 am = matrix_to_euler(R * exp_so3(-w * dt), EulerSet::k123);
    Vec3 fd;
    for (int k = 0; k < 3; ++k) fd[k] = wrap(ap[k] - am[k]) / (2 * dt);
    const Vec3 rates = euler123_rates(a, w);
    CHECK((rates - fd).norm() <= 1e-6 * (1.0 + rates.norm()));
    // And the forward map inverts it.
    CHECK((euler_rates_to_body_omega(a, rates, EulerSet::k123) - w).norm() <
          1e-12 * (1 + w.norm()));
  }
  // At gimbal lock the small-angle value (w itself) is returned, finite.
  const Vec3 w(0.3, -0.2, 0.1);
  CHECK(euler123_rates(Vec3(0.4, kPi / 2, -0.3), w) == w);
  CHECK(euler123_rates(Vec3(0, 0, 0), w).isApprox(w));
}

TEST_CASE("euler_rates_to_world_omega matches dR/dt R^T", "[rotation]") {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const double dt = 1e-6;
  for (EulerSet set : {EulerSet::k123, EulerSet::k313}) {
    for (int i = 0; i < 1000; ++i) {
      const Vec3 a(u(rng), u(rng), u(rng));  // any angles, locks included
      const Vec3 rates(u(rng), u(rng), u(rng));
      const Mat3 Rd =
          (ref_matrix(a + dt * rates, set) - ref_matrix(a - dt * rates, set)) / (2 * dt);
      const Mat3 W = Rd * ref_matrix(a, set).transpose();  // [w_world]x
      const Vec3 w_ref(W(2, 1), W(0, 2), W(1, 0));
      const Vec3 w = euler_rates_to_world_omega(a, rates, set);
      CHECK((w - w_ref).norm() < 1e-8 * (1.0 + w.norm()));
      const Vec3 wb = euler_rates_to_body_omega(a, rates, set);
      CHECK((ref_matrix(a, set) * wb - w).norm() < 1e-13 * (1.0 + w.norm()));
    }
  }
}

TEST_CASE("Ridgely 2001, §4.4.1: free-satellite initial angular velocity", "[rotation]") {
  // 3-1-3 angles psi = 180 deg, theta = 30 deg, phi = 0; torque-free axisymmetric
  // steady precession with Ixx = 1, Izz = 0.25: psi_dot = Izz phi_dot /
  // ((Ixx - Izz) cos theta), theta_dot = 0, phi_dot = 1 [rad/s].
  const double Ixx = 1.0, Izz = 0.25, theta = kPi / 6, phi_dot = 1.0;
  const double psi_dot = Izz * phi_dot / ((Ixx - Izz) * std::cos(theta));
  CHECK(psi_dot == Approx(0.3849).margin(1e-4));
  const Vec3 angles(kPi, theta, 0.0);
  const Vec3 rates(psi_dot, 0.0, phi_dot);
  const Vec3 w = euler_rates_to_world_omega(angles, rates, EulerSet::k313);

  // Independent: w = psi_dot z + theta_dot Rz(psi) x + phi_dot Rz(psi) Rx(theta) z.
  using AA = Eigen::AngleAxisd;
  const Mat3 Rz = AA(kPi, Vec3::UnitZ()).toRotationMatrix();
  const Mat3 Rx = AA(theta, Vec3::UnitX()).toRotationMatrix();
  const Vec3 w_ref =
      psi_dot * Vec3::UnitZ() + 0.0 * (Rz * Vec3::UnitX()) + phi_dot * (Rz * Rx * Vec3::UnitZ());
  CHECK((w - w_ref).norm() < 1e-14);

  // Sign convention (standard active rotations, R body->world): Rx(30 deg) z =
  // (0, -1/2, cos 30), then Rz(180 deg) flips it to (0, +1/2, cos 30); so
  // w_world = (0, +0.5, 0.3849 + 0.8660) = (0, +0.5, 1.2509) rad/s, matching the
  // seed's w0 ~ (0, 0.5, 1.251) with a positive y component.
  CHECK(std::abs(w.x()) < 1e-12);
  CHECK(std::abs(std::abs(w.y()) - 0.5) < 1e-3);
  CHECK(std::abs(std::abs(w.z()) - 1.2513) < 1e-3);
  CHECK(w.y() > 0.0);
  CHECK(w.z() > 0.0);
  CHECK(w.y() == Approx(0.5).margin(1e-12));
  CHECK(w.z() == Approx(psi_dot + std::cos(theta)).margin(1e-12));
  // Body frame: R^T w, and |w| is preserved.
  const Vec3 wb = euler_rates_to_body_omega(angles, rates, EulerSet::k313);
  CHECK(std::abs(wb.norm() - w.norm()) < 1e-12);
  // Body z component = phi_dot + psi_dot cos(theta) (classic result).
  CHECK(wb.z() == Approx(phi_dot + psi_dot * std::cos(theta)).margin(1e-12));
}

TEST_CASE("quat_to_rotation_vector", "[rotation]") {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> ang(0.0, kPi);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const double th = ang(rng);
    const Quat q(Eigen::AngleAxisd(th, axis));
    const Vec3 r = quat_to_rotation_vector(q);
    CHECK((r - th * axis).norm() < 1e-12);
    // -q: same rotation vector (shortest rotation).
    const Quat mq(-q.w(), -q.x(), -q.y(), -q.z());
    CHECK((quat_to_rotation_vector(mq) - th * axis).norm() < 1e-12);
    // A rotation by th + pi... i.e. 2pi - th about axis == th about -axis.
    const Quat q2(Eigen::AngleAxisd(2 * kPi - th, axis));
    CHECK((quat_to_rotation_vector(q2) + th * axis).norm() < 1e-12);
    CHECK(quat_to_rotation_vector(q2).norm() <= kPi + 1e-15);
  }
  // Tiny angles: relative accuracy, no 0/0.
  for (double th : {0.0, 1e-300, 1e-20, 1e-12, 1e-9, 1e-7, 1e-5}) {
    const Vec3 axis = Vec3(1, -2, 3).normalized();
    const Quat q(Eigen::AngleAxisd(th, axis));
    const Vec3 r = quat_to_rotation_vector(q);
    REQUIRE(r.allFinite());
    CHECK((r - th * axis).norm() <= 1e-15 * th);
  }
  CHECK(quat_to_rotation_vector(Quat::Identity()) == Vec3::Zero());
  CHECK(quat_to_rotation_vector(Quat(0, 0, 0, 0)) == Vec3::Zero());
  // Half turn: angle pi exactly.
  const Vec3 r = quat_to_rotation_vector(Quat(0, 0, 1, 0));
  CHECK((r - Vec3(0, kPi, 0)).norm() < 1e-15);
}

TEST_CASE("normalized_or_identity", "[rotation]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto is_identity = [](const Quat& q) {
    return q.w() == 1.0 && q.x() == 0.0 && q.y() == 0.0 && q.z() == 0.0;
  };
  CHECK(is_identity(normalized_or_identity(Quat(nan, 0, 0, 0))));
  CHECK(is_identity(normalized_or_identity(Quat(1, nan, 0, 0))));
  CHECK(is_identity(normalized_or_identity(Quat(nan, nan, nan, nan))));
  CHECK(is_identity(normalized_or_identity(Quat(inf, 0, 0, 0))));
  CHECK(is_identity(normalized_or_identity(Quat(0, 0, 0, 0))));
  CHECK(is_identity(normalized_or_identity(Quat(1e-200, 0, 0, 0))));
  const Quat q = normalized_or_identity(Quat(2, 0, 0, -2));
  CHECK(q.w() == Approx(std::sqrt(0.5)));
  CHECK(q.z() == Approx(-std::sqrt(0.5)));
  CHECK(std::abs(q.norm() - 1.0) < 1e-15);
  // Large finite values do not overflow.
  const Quat big = normalized_or_identity(Quat(1e300, 1e300, 0, 0));
  CHECK(big.w() == Approx(std::sqrt(0.5)));
  CHECK(big.x() == Approx(std::sqrt(0.5)));
}
