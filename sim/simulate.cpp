#include "sim/simulate.hpp"

#include <cmath>
#include <stdexcept>

#include "sim/reduced/simulator.hpp"
#include "sim/reduced/stride_fit.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"

namespace pronk {

namespace {

RunResult run_full(const scene::Scene& s, const RunOptions& o) {
  if (o.start_at_touchdown) {
    throw std::invalid_argument(
        "the full model starts from a rigid initial state, not at a touchdown");
  }
  robot::RobotRunOptions ro;
  ro.record_trajectory = o.record_trajectory;
  RunResult r;
  static_cast<robot::RobotRunResult&>(r) = robot::simulate(s, ro);
  return r;
}

RunResult run_reduced(const scene::Scene& s, const RunOptions& o) {
  reduced::RunOptions ro;
  ro.record_trajectory = o.record_trajectory;
  ro.record_strides = o.record_strides;
  ro.start_at_touchdown = o.start_at_touchdown;
  RunResult r;
  r.run = reduced::simulate(s, ro);
  return r;
}

}  // namespace

RunResult simulate(const scene::Scene& scene, const RunOptions& options) {
  RunResult r;
  switch (scene.model) {
    case scene::ModelKind::kImpulse:
    case scene::ModelKind::kPulse:
      r = run_reduced(scene, options);
      break;
    case scene::ModelKind::kPseudoRigid:
    case scene::ModelKind::kMujoco:
      r = run_full(scene, options);
      break;
  }
  r.model = scene.model;
  return r;
}

void check_buildable(const scene::Scene& scene) {
  if (scene::is_full_model(scene.model)) robot::build_robot(scene);
}

StabilityEstimate analyze_stability(const scene::Scene& scene, double penalty) {
  StabilityEstimate e;
  if (scene::is_full_model(scene.model)) {
    // No touchdown state can start the full model: fit the map to disturbed runs.
    RunOptions o;
    o.record_trajectory = false;
    long strides = 0;
    const auto run = [&](const scene::Scene& s) {
      reduced::RunResult r = simulate(s, o).run;
      strides += static_cast<long>(r.strides.size());
      return r;
    };
    const reduced::StrideFitOptions fo;
    const reduced::StrideFitResult f = reduced::estimate_stride_map(scene, run, fo, penalty);
    e.ok = f.ok;
    e.reason = f.ok ? "" : "no stride-map estimate: " + f.reason;
    e.spectral_radius = f.spectral_radius;
    e.method = "stride_map_fit";
    e.simulations = fo.runs;
    e.strides = strides;
    e.fit_residual = f.residual_rel;
  } else {
    const reduced::StabilityResult r = reduced::analyze_stability(scene, {}, penalty);
    e.ok = r.ok;
    e.reason = r.reason;
    e.spectral_radius = r.spectral_radius;
    e.method = "orbit_jacobian";
    e.simulations = r.map_evaluations;
    e.strides = r.map_evaluations;
  }
  if (!std::isfinite(e.spectral_radius)) e.spectral_radius = penalty;
  return e;
}

}  // namespace pronk
