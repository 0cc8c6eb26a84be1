// Shared helpers of the extreme-case tests (docs/models.md, issue 7 "the extremes"): an
// independent rigid-body reference (Euler's equations with a quaternion,
// integrated tightly) and checks that every number a run reports is finite.
#pragma once

#include <cmath>
#include <map>
#include <string>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/reduced/run_result.hpp"

namespace pronk::test::extremes {

/// Torque-free rigid body: y = [q (w, x, y, z), omega_body]; principal moments i [kg m^2].
class EulerEquations final : public ode::OdeSystem {
 public:
  explicit EulerEquations(const Eigen::Vector3d& i) : i_(i) {}
  int dimension() const override { return 7; }
  void rhs(double, const ode::Vec& y, ode::Vec& f) const override {
    const Eigen::Quaterniond q(y[0], y[1], y[2], y[3]);
    const Eigen::Vector3d w = y.segment<3>(4);
    const Eigen::Quaterniond qd = q * Eigen::Quaterniond(0.0, w.x(), w.y(), w.z());
    f[0] = 0.5 * qd.w();
    f[1] = 0.5 * qd.x();
    f[2] = 0.5 * qd.y();
    f[3] = 0.5 * qd.z();
    f.segment<3>(4) = (-w.cross(i_.cwiseProduct(w))).cwiseQuotient(i_);
  }

 private:
  Eigen::Vector3d i_;
};

/// World angular velocity [rad/s] at time t of a free rigid body with principal
/// moments i, initial attitude r0 (body -> world) and initial world angular velocity
/// w0, from Euler's equations integrated by DOPRI5 at 1e-12.
inline Eigen::Vector3d reference_world_omega(const Eigen::Vector3d& i, const Eigen::Matrix3d& r0,
                                             const Eigen::Vector3d& w0, double t) {
  EulerEquations sys(i);
  const Eigen::Quaterniond q0(r0);
  ode::Vec y(7);
  y << q0.w(), q0.x(), q0.y(), q0.z(), r0.transpose() * w0;
  ode::SolverOptions o;
  o.rtol = o.atol = 1e-12;
  o.h_max = 0.01;
  auto s = ode::make_stepper(o, 7);
  s->reset(sys, 0.0, y);
  ode::integrate(sys, *s, t, {}, o);
  const Eigen::Quaterniond q(s->y()[0], s->y()[1], s->y()[2], s->y()[3]);
  return q.normalized() * Eigen::Vector3d(s->y().segment<3>(4));
}

/// True when every number of a pseudo-rigid run summary is finite.
inline bool all_finite(const pseudorigid::RunSummary& r) {
  bool ok = std::isfinite(r.energy_scale) && std::isfinite(r.energy_drift) &&
            std::isfinite(r.max_strain) && std::isfinite(r.max_penetration) &&
            std::isfinite(r.jacobian_check_error) && std::isfinite(r.t_reached) &&
            std::isfinite(r.wall_time) && r.energy_scale > 0.0;
  for (double f : r.max_surface_force) ok = ok && std::isfinite(f);
  for (size_t i = 0; i < r.t.size(); ++i) {
    ok = ok && std::isfinite(r.t[i]) && r.y[i].allFinite() &&
         std::isfinite(r.energies[i].total()) && std::isfinite(r.dissipated[i]) &&
         std::isfinite(r.actuator_work[i]);
  }
  return ok;
}

/// True when every number of a reduced run result is finite.
inline bool all_finite(const reduced::RunResult& r) {
  bool ok = std::isfinite(r.t_end) && r.final_position.allFinite() &&
            r.final_velocity.allFinite() && r.final_euler123.allFinite() &&
            r.final_omega.allFinite() && r.final_attitude.coeffs().allFinite() &&
            std::isfinite(r.monitors.max_event_residual) &&
            std::isfinite(r.monitors.max_flight_energy_drift) &&
            std::isfinite(r.monitors.max_quaternion_norm_error) && std::isfinite(r.cost.wall_time);
  for (const auto& s : r.trajectory) {
    ok = ok && std::isfinite(s.t) && s.position.allFinite() && s.velocity.allFinite() &&
         s.euler123.allFinite() && s.omega.allFinite() && s.setpoint.allFinite() &&
         s.leg_force_world.allFinite();
  }
  for (const auto& s : r.strides) {
    ok = ok && s.position.allFinite() && s.velocity.allFinite() && s.euler123.allFinite() &&
         s.omega.allFinite() && s.P_delivered.allFinite() && s.H_delivered.allFinite() &&
         std::isfinite(s.apex_height) && std::isfinite(s.duty_cycle) &&
         std::isfinite(s.peak_leg_force);
  }
  return ok;
}

}  // namespace pronk::test::extremes
