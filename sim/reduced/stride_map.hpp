// Gait stability: the touchdown-to-touchdown (Poincaré) map in coordinates
// relative to the moving setpoint, its periodic orbit (fixed point) and the
// eigenvalues of its finite-difference linearisation (docs/studies.md). Stable
// running: spectral radius < 1.
#pragma once

#include <string>

#include <Eigen/Core>

#include "sim/scene/scene.hpp"

namespace pronk::reduced {

/// Touchdown state relative to the setpoint (11 numbers): x - x_d, y - y_d [m],
/// vx - v_dx, vy - v_dy, vz [m/s], attitude error (rotation vector of q_h^-1 q,
/// q_h the level attitude at the setpoint heading) [rad], body rates [rad/s].
/// The height is not a coordinate: it is the leg length at every touchdown.
constexpr int kStrideStateSize = 11;
using StrideState = Eigen::Matrix<double, kStrideStateSize, 1>;

struct StrideMapResult {
  bool ok = false;
  std::string reason;  ///< why not ok (fell, diverged, no touchdown)
  StrideState next = StrideState::Zero();
  double period = 0.0;  ///< time to the touchdown that ends the map [s]
};

/// Applies the map: from touchdown state s, the controller acts at once and the
/// model runs to the touchdown after `period_strides` strides (the gait's period).
StrideMapResult stride_map(const scene::Scene& scene, const StrideState& s);

/// Strides in one period of the gait (alternating gaits: the number of groups).
int gait_period(const scene::Scene& scene);

struct StabilityOptions {
  int max_settle_iterations = 200;  ///< map iterations towards the orbit before Newton
  int max_newton_iterations = 10;
  double orbit_tolerance = 1e-10;  ///< |F(s) - s|_inf at the fixed point
  double fd_step = 1e-6;           ///< central-difference step in every coordinate
  double rtol = 1e-11;             ///< solver tolerance for the map (smooth enough to difference)
};

struct StabilityResult {
  bool ok = false;  ///< orbit found and linearised
  std::string reason;
  StrideState fixed_point = StrideState::Zero();
  double orbit_residual = 0.0;  ///< |F(s*) - s*|_inf
  Eigen::Matrix<double, kStrideStateSize, kStrideStateSize> jacobian =
      Eigen::Matrix<double, kStrideStateSize, kStrideStateSize>::Zero();
  Eigen::Matrix<std::complex<double>, kStrideStateSize, 1> multipliers;
  double spectral_radius = 0.0;  ///< max |multiplier|; a finite penalty when !ok
  double period = 0.0;           ///< period of the orbit [s]
  long map_evaluations = 0;
};

/// Finds the periodic orbit and its multipliers. Never throws; when no orbit is
/// found (the gait falls or wanders) ok is false and spectral_radius = `penalty`.
StabilityResult analyze_stability(const scene::Scene& scene, const StabilityOptions& options = {},
                                  double penalty = 10.0);

}  // namespace pronk::reduced
