// The stride-map estimator (fit of an affine map to touchdown states of disturbed
// runs) against independent references: an exactly affine map it must recover to
// rounding, and the pulse model's stride map linearised by finite differences
// (reduced::analyze_stability) on the legged hopper.
#include "sim/reduced/stride_fit.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "sim/math/rotation.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/reduced/stride_map.hpp"
#include "tests/support/scenes.hpp"

using namespace pronk;
using reduced::StrideState;

namespace {

/// A stride record whose touchdown state is s (setpoint at the origin at t = 0).
reduced::StrideRecord record_of(const scene::Scene& sc, const StrideState& s) {
  reduced::StrideRecord r;
  const Eigen::Vector3d v_d = sc.controller.setpoint_velocity;
  r.setpoint = sc.controller.setpoint_position;
  r.position = Eigen::Vector3d(s[0] + r.setpoint.x(), s[1] + r.setpoint.y(), sc.legs.length);
  r.velocity = Eigen::Vector3d(s[2] + v_d.x(), s[3] + v_d.y(), s[4]);
  const Eigen::Vector3d rv = s.segment<3>(5);
  const math::Quat q =
      math::Quat(Eigen::AngleAxisd(sc.controller.setpoint_yaw, Eigen::Vector3d::UnitZ())) *
      (rv.norm() > 0 ? math::Quat(Eigen::AngleAxisd(rv.norm(), rv.normalized()))
                     : math::Quat::Identity());
  r.euler123 = math::quat_to_euler(q, math::EulerSet::k123);
  r.omega = s.segment<3>(8);
  return r;
}

reduced::RunResult run_reduced(const scene::Scene& s) {
  reduced::RunOptions o;
  o.record_trajectory = false;
  return reduced::simulate(s, o);
}

}  // namespace

TEST_CASE("the stride-map fit recovers an exactly affine map", "[reduced][stride_fit]") {
  scene::Scene sc = test::load_shipped("case3_legged_pulse");
  sc.controller.setpoint_yaw = 0.3;  // the attitude coordinates are relative to the heading
  // A known map: a stable random matrix with a complex pair, scaled to radius 0.8.
  using Mat = Eigen::Matrix<double, reduced::kStrideStateSize, reduced::kStrideStateSize>;
  Mat A = Mat::Random();
  const double rho = Eigen::EigenSolver<Mat>(A, false).eigenvalues().cwiseAbs().maxCoeff();
  A *= 0.8 / rho;
  StrideState b = 0.01 * StrideState::Random();
  const StrideState fixed = (Mat::Identity() - A).fullPivLu().solve(b);
  std::vector<std::vector<reduced::StrideRecord>> runs;
  for (int k = 0; k < 3; ++k) {
    StrideState s = fixed + 0.02 * StrideState::Random();
    std::vector<reduced::StrideRecord> run;
    for (int i = 0; i < 10; ++i) {
      const reduced::StrideRecord r = record_of(sc, s);
      // The record's coordinates round-trip (touchdown_state inverts record_of).
      CHECK((reduced::touchdown_state(sc, r) - s).cwiseAbs().maxCoeff() < 1e-12);
      run.push_back(r);
      s = A * s + b;
    }
    runs.push_back(run);
  }
  const reduced::StrideFitResult fit = reduced::fit_stride_map(sc, runs);
  INFO(fit.reason);
  REQUIRE(fit.ok);
  CHECK(fit.pairs == 27);
  CHECK(fit.rank == 12);
  CHECK(fit.residual_rel < 1e-9);
  CHECK((fit.jacobian - A).cwiseAbs().maxCoeff() < 1e-8);
  CHECK((fit.fixed_point - fixed).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(fit.spectral_radius == Approx(0.8).epsilon(1e-8));
  // Too few strides: not an estimate, the penalty instead.
  runs.resize(1);
  const reduced::StrideFitResult few = reduced::fit_stride_map(sc, runs, {}, 42.0);
  CHECK_FALSE(few.ok);
  CHECK(few.spectral_radius == 42.0);
  CHECK(few.reason.find("too few strides") != std::string::npos);
}

TEST_CASE("the stride-map fit agrees with the pulse model's finite-difference stride map",
          "[reduced][stride_fit]") {
  // The legged hopper (case 3) at stance pulses from 11 % to 40 % duty; the last is
  // unstable (radius 1.04), and the fit must say so too. Tolerance: 2e-3 on the radius
  // (the fit's error is of the order of its perturbations, ~1e-3 here; measured 1e-4 to 4e-4),
  // 1e-4 on the fixed point [m, m/s, rad, rad/s].
  scene::Scene base = test::load_shipped("case3_legged_pulse");
  base.model = scene::ModelKind::kPulse;
  for (double T : {0.05, 0.1, 0.2, 0.3}) {
    scene::Scene s = base;
    s.pulse.duration = T;
    const reduced::StabilityResult ref = reduced::analyze_stability(s);
    REQUIRE(ref.ok);
    const reduced::StrideFitResult fit = reduced::estimate_stride_map(s, run_reduced);
    INFO("T = " << T << " s: stride map " << ref.spectral_radius << ", fit " << fit.spectral_radius
                << " (" << fit.reason << ")");
    REQUIRE(fit.ok);
    CHECK(fit.runs_fell == 0);
    CHECK(fit.rank == 12);
    CHECK(fit.residual_rel < 0.01);
    CHECK(std::abs(fit.spectral_radius - ref.spectral_radius) < 2e-3);
    CHECK((fit.fixed_point - ref.fixed_point).cwiseAbs().maxCoeff() < 1e-4);
    CHECK((fit.spectral_radius < 1.0) == (ref.spectral_radius < 1.0));
    // The whole linearisation, not only its largest multiplier.
    CHECK((fit.jacobian - ref.jacobian).norm() < 0.05 * ref.jacobian.norm());
  }
}
