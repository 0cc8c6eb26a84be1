// The reduced simulator: impulse and pulse Newton-Euler models of a body
// hopping on massless legs (Ridgely 2001, §2.4-2.6, App. A.1; docs/models.md). One call runs one
// scene; the scene is const and may be shared by threads, every run owns its
// state, event log, counters and warnings.
#pragma once

#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

struct RunOptions {
  bool record_trajectory = true;  ///< sample the trajectory every scene.simulation.sample_interval
  bool record_strides = true;     ///< keep the per-stride records
  /// Treat the initial state as a touchdown at t = 0 (the controller acts at
  /// once): used to evaluate the touchdown-to-touchdown stride map.
  bool start_at_touchdown = false;
};

/// Simulates the scene with its model (impulse or pulse). Never throws for
/// numerical trouble: falls and divergence end the run with a status and reason; a fixed
/// step too long to see every flight ends it `diverged` at t = 0 (run_limits.hpp). Throws
/// std::invalid_argument (the numbers in the message) when the run would hold more records
/// than run_limits.hpp allows: more trajectory samples (recorded) or strides (recorded).
RunResult simulate(const scene::Scene& scene, const RunOptions& options = {});

}  // namespace pronk::reduced
