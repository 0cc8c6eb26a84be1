// An estimate of the stride map's linearisation from simulated runs, for models
// whose stride map cannot be evaluated from an arbitrary touchdown state (the
// pseudo-rigid robot: its runs start from a rigid initial state, not at a
// touchdown). Model-agnostic: it needs only the touchdown records of a few
// disturbed runs.
//
// Method: a few runs start at the nominal apex (CoM at the setpoint, l + h high,
// level at the setpoint heading, moving with the setpoint velocity) plus small
// seeded perturbations of position, velocity, attitude and body rates. Every
// pair of touchdown states one gait period apart, (s_k, s_{k+P}) in the stride
// map's coordinates (stride_map.hpp), is a sample of the map F. An affine map
// s_{k+P} = A s_k + b is fitted to all pairs by least squares (columns scaled to
// unit spread, minimum-norm SVD solve), so neither the orbit nor the Jacobian
// is assumed: the fixed point is s* = (I - A)^-1 b and the multipliers are the
// eigenvalues of A. Near the orbit F(s) = s* + J (s - s*) + O(|s - s*|^2), so A
// estimates J with an error of the order of the perturbation size (the
// quadratic terms) plus the runs' own integration error divided by the
// perturbation size; the fit's residual reports both.
#pragma once

#include <complex>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/reduced/run_result.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

/// The touchdown state of a stride record in the stride map's coordinates:
/// x - x_d, y - y_d [m], vx - v_dx, vy - v_dy, vz [m/s], attitude error
/// (rotation vector of q_h^-1 q) [rad], body rates [rad/s].
StrideState touchdown_state(const scene::Scene& scene, const StrideRecord& record);

/// The perturbations are small enough for the map to be nearly linear (the fit's error
/// grows with their size) and large against the integration error of the runs (which the
/// fit divides by their size): on the legged hopper the estimate moves by < 1e-3 between
/// 3x and 0.3x these sizes, for the pulse model and the pseudo-rigid robot alike.
struct StrideFitOptions {
  int runs = 4;                  ///< disturbed runs
  double duration = 6.0;         ///< simulated time per run [s]
  std::uint64_t seed = 1;        ///< of the perturbations
  double position = 0.002;       ///< largest initial horizontal offset per axis [m]
  double height = 0.001;         ///< largest initial height offset from l + h [m]
  double velocity = 0.005;       ///< largest initial horizontal velocity offset per axis [m/s]
  double tilt = 0.0035;          ///< largest initial roll, pitch and yaw [rad] (0.2 deg)
  double rate = 0.02;            ///< largest initial body rate per axis [rad/s]
  double rank_tolerance = 1e-9;  ///< singular values below this x the largest are dropped
};

struct StrideFitResult {
  bool ok = false;
  std::string reason;  ///< why not ok
  StrideState fixed_point = StrideState::Zero();
  Eigen::Matrix<double, kStrideStateSize, kStrideStateSize> jacobian =
      Eigen::Matrix<double, kStrideStateSize, kStrideStateSize>::Zero();
  Eigen::Matrix<std::complex<double>, kStrideStateSize, 1> multipliers =
      Eigen::Matrix<std::complex<double>, kStrideStateSize, 1>::Zero();
  double spectral_radius = 0.0;  ///< max |multiplier|; the penalty when !ok
  long pairs = 0;                ///< samples (s_k, s_{k+P}) fitted
  int rank = 0;                  ///< of the scaled regression (12 = every direction excited)
  /// RMS of the fit's residuals over the RMS of the centred next states (0: exactly affine).
  double residual_rel = 0.0;
  long runs_fell = 0;  ///< runs that did not complete (their strides before the fall are used)
};

/// Fits the affine stride map to the touchdown records of `runs` (each a run of `scene`).
/// Never throws; fewer than 2 x 12 pairs or no invertible I - A give ok = false.
StrideFitResult fit_stride_map(const scene::Scene& scene,
                               const std::vector<std::vector<StrideRecord>>& runs,
                               const StrideFitOptions& options = {}, double penalty = 10.0);

/// The scenes of the disturbed runs (options.runs of them, deterministic in options.seed).
std::vector<scene::Scene> stride_fit_scenes(const scene::Scene& scene,
                                            const StrideFitOptions& options = {});

/// Runs `simulate` on every stride_fit_scenes() scene and fits their records.
StrideFitResult estimate_stride_map(const scene::Scene& scene,
                                    const std::function<RunResult(const scene::Scene&)>& simulate,
                                    const StrideFitOptions& options = {}, double penalty = 10.0);

}  // namespace pronk::reduced
