// The reduced simulator: impulse and pulse Newton-Euler models of a body
// hopping on massless legs (SPEC 2; seed 2.4-2.6, A.1). One call runs one
// scene; the scene is const and may be shared by threads, every run owns its
// state, event log, counters and warnings.
#pragma once

#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

struct RunOptions {
  bool record_trajectory = true;  ///< sample the trajectory every scene.simulation.sample_interval
  bool record_strides = true;     ///< keep the per-stride records
};

/// Simulates the scene with its model (impulse or pulse). Never throws for
/// numerical trouble: falls and divergence end the run with a status and reason.
RunResult simulate(const scene::Scene& scene, const RunOptions& options = {});

}  // namespace pronk::reduced
