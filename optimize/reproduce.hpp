// Reproducing a tuned design (design.json of `pronk optimize`): its study is
// re-read from the design, the design re-evaluated on the study's scenarios and
// validation set, and every recorded metric compared: bit-identical on the
// recording build (same commit and compiler), within a relative tolerance on another.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::optimize {

struct ReproducedValue {
  std::string name;  ///< "cost", a metric, or "validation <metric>"
  double recorded = 0.0;
  double reproduced = 0.0;  ///< NaN when the re-evaluation no longer reports the metric
  bool ok = false;
};

struct ReproduceReport {
  bool same_build = false;  ///< recorded by this commit and compiler: bit-identical required
  double rtol = 1e-6;       ///< the tolerance when !same_build
  std::vector<ReproducedValue> values;
  long mismatches = 0;
};

/// Re-evaluates `design` (read from `path`, named in errors; a relative scene path of
/// its study resolves against the path's directory) with `threads` workers.
/// Throws io::InputError when it is not a design.json or lacks a recorded value.
ReproduceReport reproduce_design(const nlohmann::json& design, const std::string& path, int threads,
                                 double rtol);

}  // namespace pronk::optimize
