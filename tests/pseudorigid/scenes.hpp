// Mechanism scenes shared by the pseudo-rigid tests (and mirrored by the
// studies/mechanisms/*.json files and bench_pseudorigid).
#pragma once

#include <cmath>

#include "sim/math/rotation.hpp"
#include "sim/pseudorigid/builder.hpp"

namespace pronk::pseudorigid::test_scenes {

/// Case 10 (Ridgely 2001, §4.4.1): axisymmetric satellite Ixx = Iyy = 1, Izz = 0.25 kg m^2, four
/// 1 kg masses, 3-1-3 angles (180, 30, 0) deg, spin 1 rad/s, steady precession.
inline Mechanism satellite(double k, double t_end) {
  Mechanism m;
  m.name = "satellite";
  m.gravity.setZero();
  BodySpec b;
  b.name = "satellite";
  b.mass = 4.0;
  b.inertia = Eigen::Vector3d(1.0, 1.0, 0.25).asDiagonal();
  const Eigen::Vector3d angles(M_PI, M_PI / 6.0, 0.0);
  b.attitude = math::euler_to_matrix(angles, math::EulerSet::k313);
  const double theta = M_PI / 6.0;
  const double spin = 1.0;
  const double precession = 0.25 * spin / (0.75 * std::cos(theta));
  b.omega = math::euler_rates_to_world_omega(angles, Eigen::Vector3d(precession, 0.0, spin),
                                             math::EulerSet::k313);
  b.internal_stiffness = k;
  std::string err;
  add_body(m, b, &err);
  m.simulation.t_end = t_end;
  m.simulation.output_interval = 0.1;
  m.simulation.euler_313 = true;
  return m;
}

/// Exact world angular velocity of the satellite at time t [rad/s].
inline Eigen::Vector3d satellite_omega(double t) {
  const double theta = M_PI / 6.0, spin = 1.0;
  const double precession = 0.25 * spin / (0.75 * std::cos(theta));
  const double psi = M_PI + precession * t;
  return Eigen::Vector3d(std::sin(theta) * std::sin(psi), -std::sin(theta) * std::cos(psi),
                         std::cos(theta)) *
             spin +
         Eigen::Vector3d(0, 0, precession);
}

}  // namespace pronk::pseudorigid::test_scenes
