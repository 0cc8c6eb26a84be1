#include "sim/reduced/stride_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "sim/math/rotation.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::reduced {

using Eigen::Vector3d;

namespace {

math::Quat heading(const scene::Scene& scene) {
  return math::Quat(Eigen::AngleAxisd(scene.controller.setpoint_yaw, Vector3d::UnitZ()));
}

/// SplitMix64: a portable generator, so the perturbations are the same everywhere.
class Mix {
 public:
  explicit Mix(std::uint64_t seed) : state_(seed) {}
  /// Uniform in [-1, 1].
  double symmetric() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return 2.0 * static_cast<double>(z >> 11) * 0x1.0p-53 - 1.0;
  }

 private:
  std::uint64_t state_;
};

}  // namespace

StrideState touchdown_state(const scene::Scene& scene, const StrideRecord& r) {
  const Vector3d v_d = scene.controller.setpoint_velocity;
  StrideState s;
  s[0] = r.position.x() - r.setpoint.x();
  s[1] = r.position.y() - r.setpoint.y();
  s[2] = r.velocity.x() - v_d.x();
  s[3] = r.velocity.y() - v_d.y();
  s[4] = r.velocity.z();
  const math::Quat q = math::euler_to_quat(r.euler123, math::EulerSet::k123);
  s.segment<3>(5) = math::quat_to_rotation_vector(heading(scene).conjugate() * q);
  s.segment<3>(8) = r.omega;
  return s;
}

std::vector<scene::Scene> stride_fit_scenes(const scene::Scene& base, const StrideFitOptions& o) {
  std::vector<scene::Scene> out;
  Mix g(o.seed);
  for (int k = 0; k < o.runs; ++k) {
    scene::Scene s = base;
    s.disturbances.clear();
    s.simulation.duration = o.duration;
    s.simulation.max_strides = 1000000;
    const Vector3d x_d = base.controller.setpoint_position;
    s.initial.position =
        Vector3d(x_d.x() + o.position * g.symmetric(), x_d.y() + o.position * g.symmetric(),
                 base.legs.length + base.controller.hop_height + o.height * g.symmetric());
    s.initial.velocity = base.controller.setpoint_velocity;
    s.initial.velocity.z() = 0.0;
    s.initial.velocity.x() += o.velocity * g.symmetric();
    s.initial.velocity.y() += o.velocity * g.symmetric();
    const Vector3d tilt(o.tilt * g.symmetric(), o.tilt * g.symmetric(), o.tilt * g.symmetric());
    s.initial.attitude =
        (heading(base) * math::euler_to_quat(tilt, math::EulerSet::k123)).normalized();
    s.initial.angular_velocity =
        Vector3d(o.rate * g.symmetric(), o.rate * g.symmetric(), o.rate * g.symmetric());
    out.push_back(std::move(s));
  }
  return out;
}

StrideFitResult fit_stride_map(const scene::Scene& scene,
                               const std::vector<std::vector<StrideRecord>>& runs,
                               const StrideFitOptions& o, double penalty) {
  constexpr int n = kStrideStateSize;
  StrideFitResult res;
  res.spectral_radius = penalty;
  const size_t P = static_cast<size_t>(gait_period(scene));
  std::vector<StrideState> xs, ys;
  for (const auto& strides : runs) {
    for (size_t k = 0; k + P < strides.size(); ++k) {
      const StrideState a = touchdown_state(scene, strides[k]);
      const StrideState b = touchdown_state(scene, strides[k + P]);
      if (!a.allFinite() || !b.allFinite()) continue;
      xs.push_back(a);
      ys.push_back(b);
    }
  }
  res.pairs = static_cast<long>(xs.size());
  if (res.pairs < 2 * (n + 1)) {
    res.reason = "too few strides to fit: " + run::count_text(res.pairs, "pair") + " (need " +
                 std::to_string(2 * (n + 1)) + ")";
    return res;
  }
  const Eigen::Index m = static_cast<Eigen::Index>(xs.size());
  Eigen::MatrixXd X(m, n), Y(m, n);
  for (Eigen::Index i = 0; i < m; ++i) {
    X.row(i) = xs[static_cast<size_t>(i)].transpose();
    Y.row(i) = ys[static_cast<size_t>(i)].transpose();
  }
  // Centre (the intercept b follows from the means) and scale every column to unit spread.
  const Eigen::RowVectorXd xm = X.colwise().mean(), ym = Y.colwise().mean();
  X.rowwise() -= xm;
  Y.rowwise() -= ym;
  Eigen::VectorXd scale(n);
  for (int j = 0; j < n; ++j) {
    const double rms = std::sqrt(X.col(j).squaredNorm() / static_cast<double>(m));
    scale[j] = rms > 0.0 ? rms : 1.0;
  }
  const Eigen::MatrixXd Xs = X * scale.cwiseInverse().asDiagonal();
  Eigen::BDCSVD<Eigen::MatrixXd> svd(Xs, Eigen::ComputeThinU | Eigen::ComputeThinV);
  svd.setThreshold(o.rank_tolerance);
  res.rank = static_cast<int>(svd.rank()) + 1;  // + the intercept
  // Xs (D A^T) = Y  =>  A^T = D^-1 (Xs^+ Y).
  const Eigen::MatrixXd At = scale.cwiseInverse().asDiagonal() * svd.solve(Y);
  res.jacobian = At.transpose();
  const Eigen::MatrixXd R = Y - X * At;
  const double ynorm = Y.norm();
  res.residual_rel = ynorm > 0.0 ? R.norm() / ynorm : 0.0;
  const StrideState b = ym.transpose() - res.jacobian * xm.transpose();
  using Mat = Eigen::Matrix<double, n, n>;
  const Eigen::FullPivLU<Mat> lu(Mat::Identity() - res.jacobian);
  if (!lu.isInvertible()) {
    res.reason = "the fitted map has a multiplier 1: no isolated fixed point";
    return res;
  }
  res.fixed_point = lu.solve(b);
  Eigen::EigenSolver<Mat> eig(res.jacobian, false);
  if (eig.info() != Eigen::Success) {
    res.reason = "eigenvalue computation failed";
    return res;
  }
  res.multipliers = eig.eigenvalues();
  const double rho = res.multipliers.cwiseAbs().maxCoeff();
  if (!std::isfinite(rho) || !res.fixed_point.allFinite()) {
    res.reason = "non-finite fit";
    return res;
  }
  if (res.rank < n + 1) {
    // Unexcited directions get multiplier 0 from the minimum-norm solve: not an estimate.
    res.reason = "only " + std::to_string(res.rank) + " of " + std::to_string(n + 1) +
                 " directions of the state are excited by the runs";
    return res;
  }
  res.spectral_radius = rho;
  res.ok = true;
  return res;
}

StrideFitResult estimate_stride_map(const scene::Scene& scene,
                                    const std::function<RunResult(const scene::Scene&)>& simulate,
                                    const StrideFitOptions& o, double penalty) {
  std::vector<std::vector<StrideRecord>> runs;
  long fell = 0;
  for (const scene::Scene& s : stride_fit_scenes(scene, o)) {
    RunResult r = simulate(s);
    if (r.status != RunStatus::kCompleted) ++fell;
    runs.push_back(std::move(r.strides));
  }
  StrideFitResult res = fit_stride_map(scene, runs, o, penalty);
  res.runs_fell = fell;
  return res;
}

}  // namespace pronk::reduced
