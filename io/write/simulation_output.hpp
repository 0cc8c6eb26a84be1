// The output files of one simulate() run, whatever its model: the reduced
// models' set (run_output.hpp), or the full model's (robot_output.hpp) with its
// stride-by-stride discrepancy against the pulse model of the same robot.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "io/write/run_output.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/simulate.hpp"

namespace pronk::io {

/// summary.json of the run: for a full-model run with the stride-by-stride
/// discrepancy against the pulse model of the same robot (simulated here).
nlohmann::json simulation_summary_json(const scene::Scene& scene, const RunResult& r,
                                       const reduced::RunMetrics& metrics);

/// Writes the run's files into `dir`. For a full-model run the same robot is also
/// simulated in the pulse model (milliseconds) and their strides compared. Then view.html
/// (when the page templates are there: WrittenOutputs::page).
WrittenOutputs write_simulation_outputs(const std::string& dir, const scene::Scene& scene,
                                        const RunResult& r, const reduced::RunMetrics& metrics);

}  // namespace pronk::io
