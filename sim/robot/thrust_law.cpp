#include "sim/robot/thrust_law.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace pronk::robot {

namespace {

/// The legs' force on the body at (z, v) [N].
double leg_force(const ThrustModel& m, double force, double z, double v) {
  return m.stiffness * (m.z_rest - z) - m.damping * v + force;
}

/// One RK4 step of the model over h from (z, v).
void rk4_step(const ThrustModel& m, double force, double h, double& z, double& v) {
  auto accel = [&](double zz, double vv) {
    return leg_force(m, force, zz, vv) / m.mass - m.gravity;
  };
  const double a1 = accel(z, v);
  const double a2 = accel(z + 0.5 * h * v, v + 0.5 * h * a1);
  const double a3 = accel(z + 0.5 * h * (v + 0.5 * h * a1), v + 0.5 * h * a2);
  const double a4 = accel(z + h * (v + 0.5 * h * a2), v + h * a3);
  z += h * (v + h / 6.0 * (a1 + a2 + a3));
  v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
}

}  // namespace

ThrustPlan predict_thrust(const ThrustModel& m, double force) {
  ThrustPlan p;
  p.force = force;
  p.apex = m.z_bottom;
  if (!(m.mass > 0.0) || !(m.stiffness > 0.0) || leg_force(m, force, m.z_bottom, 0.0) <= 0.0) {
    return p;  // the legs cannot push: lift-off at once
  }
  const double dt = M_PI * std::sqrt(m.mass / m.stiffness) / 400.0;  // half period / 400
  double t = 0.0, z = m.z_bottom, v = 0.0;
  for (int k = 0; k < 8000; ++k) {  // 20 half periods: far past any lift-off
    double z1 = z, v1 = v;
    rk4_step(m, force, dt, z1, v1);
    const double g0 = leg_force(m, force, z, v), g1 = leg_force(m, force, z1, v1);
    if (g1 > 0.0) {
      t += dt;
      z = z1;
      v = v1;
      continue;
    }
    // Lift-off inside the step: the legs' force along sub-steps from its start, by secant.
    double sa = 0.0, ga = g0, sb = 1.0, gb = g1, zs = z1, vs = v1;
    for (int it = 0; it < 8 && gb != ga; ++it) {
      const double sc = std::clamp(sb - gb * (sb - sa) / (gb - ga), 0.0, 1.0);
      zs = z;
      vs = v;
      rk4_step(m, force, sc * dt, zs, vs);
      const double gc = leg_force(m, force, zs, vs);
      sa = sb;
      ga = gb;
      sb = sc;
      gb = gc;
      if (std::abs(gc) <= 1e-12 * m.mass * m.gravity) break;
    }
    p.duration = t + sb * dt;
    p.apex = zs + std::max(0.0, vs) * std::max(0.0, vs) / (2.0 * m.gravity);
    return p;
  }
  p.duration = t;
  p.apex = z;
  return p;
}

ThrustPlan plan_thrust(const ThrustModel& m, double apex_target, double f_min, double f_max) {
  ThrustPlan lo = predict_thrust(m, f_min);
  if (lo.apex >= apex_target) {
    lo.saturated = lo.apex > apex_target;
    return lo;
  }
  ThrustPlan hi = predict_thrust(m, f_max);
  if (hi.apex <= apex_target) {
    hi.saturated = hi.apex < apex_target;
    return hi;
  }
  for (int k = 0; k < 50 && hi.force - lo.force > 1e-9 * (1.0 + std::abs(hi.force)); ++k) {
    const ThrustPlan mid = predict_thrust(m, 0.5 * (lo.force + hi.force));
    (mid.apex < apex_target ? lo : hi) = mid;
  }
  return std::abs(hi.apex - apex_target) < std::abs(lo.apex - apex_target) ? hi : lo;
}

std::vector<double> share_thrust(double vertical, const std::vector<Eigen::Vector3d>& u,
                                 const std::vector<Eigen::Vector3d>& arm,
                                 const std::vector<double>& planned) {
  const auto n = static_cast<Eigen::Index>(u.size());
  double dz_sum = 0.0;
  for (const Eigen::Vector3d& d : u) dz_sum += d.z();
  // A f = b: the rows are the vertical share and the moments (x, y) of a unit force per leg.
  Eigen::MatrixXd A(3, n);
  Eigen::Vector3d b(vertical, 0.0, 0.0);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d moment = arm[static_cast<size_t>(k)].cross(u[static_cast<size_t>(k)]);
    A.col(k) << u[static_cast<size_t>(k)].z(), moment.x(), moment.y();
    b.tail<2>() += planned[static_cast<size_t>(k)] * moment.head<2>();
  }
  Eigen::VectorXd f = Eigen::VectorXd::Constant(n, dz_sum > 0.0 ? vertical / dz_sum : 0.0);
  const Eigen::Matrix3d AAt = A * A.transpose();
  if (n >= 3 && std::abs(AAt.determinant()) > 1e-12 * std::pow(AAt.trace(), 3)) {
    f += A.transpose() * AAt.ldlt().solve(b - A * f);
  }
  return {f.data(), f.data() + n};
}

}  // namespace pronk::robot
