// Writes one run's results into a directory: trajectory.csv, strides.csv,
// summary.json, scene.resolved.json and the seed-style figures (SVG + .gp).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "io/write/figure_batch.hpp"
#include "io/write/table.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::io {

/// The summary document (status, reason, metrics, cost, monitors, warnings).
nlohmann::json run_summary_json(const scene::Scene& scene, const reduced::RunResult& run,
                                const reduced::RunMetrics& metrics);

/// trajectory.csv and strides.csv as tables (the columns the README lists) and as text.
Table trajectory_table(const reduced::RunResult& run);
Table strides_table(const reduced::RunResult& run);
std::string trajectory_csv(const reduced::RunResult& run);
std::string strides_csv(const reduced::RunResult& run);

struct WrittenOutputs {
  bool figures_rendered = false;
  std::string page;  ///< view.html's path; empty when the page templates are absent
};

/// Writes every data file and figure script atomically into `dir` (created if missing) and
/// adds the figures to `figures`, for the caller to render once its files are all written.
void write_run_outputs(const std::string& dir, const scene::Scene& scene,
                       const reduced::RunResult& run, const reduced::RunMetrics& metrics,
                       FigureBatch& figures);

/// The same files with `summary` as summary.json (a full-model run's, written once).
void write_run_files(const std::string& dir, const scene::Scene& scene,
                     const reduced::RunResult& run, const nlohmann::json& summary,
                     FigureBatch& figures);

/// Gnuplot lines for the z axis of a 3-D CoM path from trajectory.csv (column 4): from the
/// ground, at most four round ticks, the label beside the axis.
std::string path3d_z_axis();

/// Serialises JSON after checking that it holds no non-finite number
/// (nlohmann writes NaN as null); throws std::logic_error naming the pointer.
std::string dump_checked(const nlohmann::json& j);

}  // namespace pronk::io
