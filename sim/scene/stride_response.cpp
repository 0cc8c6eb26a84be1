#include "sim/scene/stride_response.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace pronk::scene {

using Eigen::Matrix4d;
using Eigen::Vector4d;

double hop_flight_time(double gravity, double hop_height, double stance, bool pulse_aware) {
  const double v0 = std::sqrt(2.0 * gravity * hop_height);  // touchdown speed at the orbit
  if (!pulse_aware || stance <= 0.0) return 2.0 * v0 / gravity;
  // The body controller's pulse-aware law (sim/control/body_controller.cpp), at the orbit.
  const double half = 0.5 * gravity * stance;
  const double v1 =
      -half + std::sqrt(half * half + 2.0 * gravity * hop_height + gravity * v0 * stance);
  return v1 / gravity + std::sqrt(2.0 * hop_height / gravity);
}

std::array<std::complex<double>, 2> pd_channel_poles(double kp, double kd, const StrideTiming& t) {
  const double T = t.period();
  const double det = 1.0 - kd + 0.5 * kp * t.stance;
  const double trace = 1.0 + det - kp * T;
  const std::complex<double> disc = std::sqrt(std::complex<double>(trace * trace - 4.0 * det));
  return {0.5 * (trace + disc), 0.5 * (trace - disc)};
}

void pd_channel_gains(std::complex<double> z1, std::complex<double> z2, const StrideTiming& t,
                      double* kp, double* kd) {
  *kp = ((1.0 - z1) * (1.0 - z2)).real() / t.period();
  *kd = 1.0 - (z1 * z2).real() + 0.5 * *kp * t.stance;
}

Eigen::Matrix3d position_stride_map(const PositionLoop& l, const StrideTiming& t) {
  const double T = t.period(), a = T - 0.5 * t.stance;
  // Rows e', v', I' in the columns e, v, I (the trim is updated before the plan).
  const Eigen::RowVector3d v_next(-l.kp * (1.0 + l.trim), 1.0 - l.kd, -l.kp);
  Eigen::Matrix3d m;
  m.row(0) = Eigen::RowVector3d(1.0, T, 0.0) + a * (v_next - Eigen::RowVector3d(0.0, 1.0, 0.0));
  m.row(1) = v_next;
  m.row(2) << l.trim, 0.0, 1.0;
  return m;
}

PositionLoop place_position_poles(const std::array<double, 3>& poles, const StrideTiming& t) {
  const double T = t.period(), a = T - 0.5 * t.stance;
  const double q1 = poles[0] - 1.0, q2 = poles[1] - 1.0, q3 = poles[2] - 1.0;
  const double s1 = q1 + q2 + q3, s2 = q1 * q2 + q1 * q3 + q2 * q3, s3 = q1 * q2 * q3;
  // T kp g = -s3;  T kp (1 + g) + a kp g = s2;  kd + a kp (1 + g) = -s1.
  const double kp_g = -s3 / T;
  PositionLoop l;
  l.kp = (s2 - (T + a) * kp_g) / T;
  l.trim = kp_g / l.kp;
  l.kd = -s1 - a * (l.kp + kp_g);
  return l;
}

std::array<std::complex<double>, 2> response_poles(double omega, double zeta, double period) {
  const std::complex<double> root = std::sqrt(std::complex<double>(zeta * zeta - 1.0));
  const std::complex<double> s1 = omega * (-zeta + root), s2 = omega * (-zeta - root);
  return {std::exp(s1 * period), std::exp(s2 * period)};
}

namespace {

// The lateral map without feedback (A0) and the column the roll rate change enters by (c),
// in the dimensionless state (u, w, phi, W), time in strides, stance fraction s. Over the
// stance the roll rate grows linearly by dW, the roll is phi + W t + dW t^2 / (2 s), and the
// legs' push (g T / Ts per unit mass) tilted by -phi drives the lateral velocity.
void lateral_open_loop(double s, Matrix4d* a0, Vector4d* c) {
  *a0 << 1, 1, -(1 - s / 2), -(s / 2 - s * s / 3),  //
      0, 1, -1, -s / 2,                             //
      0, 0, 1, 1,                                   //
      0, 0, 0, 1;
  *c << -(s / 6 - s * s / 8), -s / 6, 1 - s / 2, 1;
}

// The feedback row r with dW = r . (u, w, phi, W).
Vector4d feedback_row(const LateralLoop& loop, const StrideTiming& t, double g) {
  const double T = t.period();
  const double k = loop.kp_roll * T, b = loop.kd_roll;
  return Vector4d(k * loop.bank_kp * g * T * T, k * loop.bank_kd * g * T, -k, -b);
}

}  // namespace

Matrix4d lateral_stride_map(const LateralLoop& loop, const StrideTiming& t, double gravity) {
  Matrix4d a0;
  Vector4d c;
  lateral_open_loop(t.stance / t.period(), &a0, &c);
  return a0 + c * feedback_row(loop, t, gravity).transpose();
}

LateralLoop place_lateral_poles(const std::array<double, 4>& poles, const StrideTiming& t,
                                double gravity) {
  Matrix4d a0;
  Vector4d c;
  lateral_open_loop(t.stance / t.period(), &a0, &c);
  Matrix4d ctrb;
  ctrb.col(0) = c;
  for (int i = 1; i < 4; ++i) ctrb.col(i) = a0 * ctrb.col(i - 1);
  // The desired characteristic polynomial evaluated at A0: prod (A0 - p_i I).
  Matrix4d p = Matrix4d::Identity();
  for (double pole : poles) p = p * (a0 - pole * Matrix4d::Identity());
  // Ackermann: the closed loop A0 + c r^T has these poles for r^T = -e4^T ctrb^-1 p(A0).
  const Vector4d r = -(p.transpose() * ctrb.transpose().fullPivLu().solve(Vector4d::UnitW()));
  const double T = t.period();
  LateralLoop loop;
  const double k = -r[2];
  loop.kp_roll = k / T;
  loop.kd_roll = -r[3];
  loop.bank_kp = r[0] / k / (gravity * T * T);
  loop.bank_kd = r[1] / k / (gravity * T);
  return loop;
}

double spectral_radius(const Matrix4d& a) {
  return Eigen::EigenSolver<Matrix4d>(a, false).eigenvalues().cwiseAbs().maxCoeff();
}

LateralLoop best_bank_gains(double kp_roll, double kd_roll, const StrideTiming& t, double gravity) {
  const double T = t.period();
  // Search in the dimensionless gains beta_p = bank_kp g T^2, beta_d = bank_kd g T.
  double best_p = 0.0, best_d = 0.0, best = std::numeric_limits<double>::infinity();
  double lo_p = 0.0, hi_p = 0.5, lo_d = 0.0, hi_d = 2.0;
  LateralLoop loop{kp_roll, kd_roll, 0.0, 0.0};
  for (int level = 0; level < 4; ++level) {
    constexpr int n = 20;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        const double bp = lo_p + (hi_p - lo_p) * i / n, bd = lo_d + (hi_d - lo_d) * j / n;
        loop.bank_kp = bp / (gravity * T * T);
        loop.bank_kd = bd / (gravity * T);
        const double rho = spectral_radius(lateral_stride_map(loop, t, gravity));
        if (rho < best) best = rho, best_p = bp, best_d = bd;
      }
    }
    const double wp = 2.0 * (hi_p - lo_p) / n, wd = 2.0 * (hi_d - lo_d) / n;
    lo_p = std::max(0.0, best_p - wp), hi_p = best_p + wp;
    lo_d = std::max(0.0, best_d - wd), hi_d = best_d + wd;
  }
  loop.bank_kp = best_p / (gravity * T * T);
  loop.bank_kd = best_d / (gravity * T);
  return loop;
}

}  // namespace pronk::scene
