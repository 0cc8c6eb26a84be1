#include "sim/reduced/stride_map.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "sim/math/rotation.hpp"
#include "sim/reduced/simulator.hpp"

namespace pronk::reduced {

using Eigen::Vector3d;

int gait_period(const scene::Scene& scene) {
  if (scene.controller.gait == scene::Gait::kAlternate && !scene.controller.gait_groups.empty()) {
    return static_cast<int>(scene.controller.gait_groups.size());
  }
  return 1;
}

namespace {

math::Quat heading(const scene::Scene& scene) {
  return math::Quat(Eigen::AngleAxisd(scene.controller.setpoint_yaw, Vector3d::UnitZ()));
}

// Rotation vector -> quaternion.
math::Quat exp_map(const Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-300) return math::Quat::Identity();
  return math::Quat(Eigen::AngleAxisd(angle, v / angle));
}

}  // namespace

StrideMapResult stride_map(const scene::Scene& base, const StrideState& s) {
  scene::Scene sc = base;
  const Vector3d v_d = base.controller.setpoint_velocity;
  // Time-invariance of the moving setpoint: start the map at t = 0 with x_d(0) = 0.
  sc.controller.setpoint_position = Vector3d::Zero();
  sc.disturbances.clear();
  sc.initial.position = Vector3d(s[0], s[1], base.legs.length);
  sc.initial.velocity = Vector3d(s[2] + v_d.x(), s[3] + v_d.y(), s[4]);
  sc.initial.attitude = heading(base) * exp_map(s.segment<3>(5));
  sc.initial.angular_velocity = s.segment<3>(8);
  sc.simulation.max_strides = gait_period(base);
  sc.simulation.duration = 1e6;
  RunOptions opts;
  opts.record_trajectory = false;
  opts.record_strides = false;
  opts.start_at_touchdown = true;
  const RunResult r = simulate(sc, opts);
  StrideMapResult out;
  if (r.status != RunStatus::kCompleted || r.cost.touchdowns < sc.simulation.max_strides + 1) {
    out.reason = r.status != RunStatus::kCompleted ? r.reason : "no touchdown ended the stride";
    return out;
  }
  const double T = r.t_end;
  out.period = T;
  out.next[0] = r.final_position.x() - v_d.x() * T;
  out.next[1] = r.final_position.y() - v_d.y() * T;
  out.next[2] = r.final_velocity.x() - v_d.x();
  out.next[3] = r.final_velocity.y() - v_d.y();
  out.next[4] = r.final_velocity.z();
  out.next.segment<3>(5) =
      math::quat_to_rotation_vector(heading(base).conjugate() * r.final_attitude);
  out.next.segment<3>(8) = r.final_omega;
  out.ok = out.next.allFinite();
  if (!out.ok) out.reason = "non-finite state";
  return out;
}

StabilityResult analyze_stability(const scene::Scene& base, const StabilityOptions& o,
                                  double penalty) {
  StabilityResult res;
  res.spectral_radius = penalty;
  res.multipliers.setZero();
  scene::Scene sc = base;
  sc.simulation.solver.rtol = std::min(sc.simulation.solver.rtol, o.rtol);
  sc.simulation.solver.atol = std::min(sc.simulation.solver.atol, o.rtol);
  auto F = [&](const StrideState& s, StrideMapResult* out) {
    ++res.map_evaluations;
    *out = stride_map(sc, s);
    return out->ok;
  };

  // 1. Settle towards the orbit from the nominal touchdown state.
  StrideState s = StrideState::Zero();
  s[4] = -std::sqrt(2.0 * base.gravity * base.controller.hop_height);
  StrideMapResult m;
  double residual = INFINITY;
  for (int k = 0; k < o.max_settle_iterations; ++k) {
    if (!F(s, &m)) {
      res.reason = "no periodic orbit: the gait failed while settling (" + m.reason + ")";
      return res;
    }
    residual = (m.next - s).lpNorm<Eigen::Infinity>();
    s = m.next;
    if (residual <= o.orbit_tolerance) break;
  }

  // Central-difference Jacobian of the map at s.
  using Mat = Eigen::Matrix<double, kStrideStateSize, kStrideStateSize>;
  auto jacobian = [&](const StrideState& at, Mat* J) {
    for (int i = 0; i < kStrideStateSize; ++i) {
      StrideState sp = at, sm = at;
      sp[i] += o.fd_step;
      sm[i] -= o.fd_step;
      StrideMapResult mp, mm;
      if (!F(sp, &mp) || !F(sm, &mm)) return false;
      J->col(i) = (mp.next - mm.next) / (2.0 * o.fd_step);
    }
    return true;
  };

  // 2. Newton on F(s) - s = 0 when settling alone did not converge (slow or unstable orbits).
  Mat J;
  for (int k = 0; k < o.max_newton_iterations && residual > o.orbit_tolerance; ++k) {
    if (!F(s, &m) || !jacobian(s, &J)) {
      res.reason = "no periodic orbit: the gait failed during the Newton search";
      return res;
    }
    const StrideState step = (J - Mat::Identity()).fullPivLu().solve(-(m.next - s));
    if (!step.allFinite()) break;
    s += step;
    if (!F(s, &m)) {
      res.reason = "no periodic orbit: Newton left the region where the gait runs";
      return res;
    }
    residual = (m.next - s).lpNorm<Eigen::Infinity>();
  }
  if (!(residual <= 1e3 * o.orbit_tolerance)) {
    res.reason = "no periodic orbit: residual " + std::to_string(residual) + " after the search";
    res.fixed_point = s;
    res.orbit_residual = std::isfinite(residual) ? residual : penalty;
    return res;
  }
  if (!F(s, &m) || !jacobian(s, &J)) {
    res.reason = "the gait failed while linearising the orbit";
    return res;
  }
  res.fixed_point = s;
  res.orbit_residual = residual;
  res.period = m.period;
  res.jacobian = J;
  Eigen::EigenSolver<Mat> eig(J, false);
  if (eig.info() != Eigen::Success) {
    res.reason = "eigenvalue computation failed";
    return res;
  }
  res.multipliers = eig.eigenvalues();
  res.spectral_radius = res.multipliers.cwiseAbs().maxCoeff();
  res.ok = std::isfinite(res.spectral_radius);
  if (!res.ok) {
    res.spectral_radius = penalty;
    res.reason = "non-finite multipliers";
  }
  return res;
}

}  // namespace pronk::reduced
