// The robustness-map engine (docs/maps.md): the scene of a cell, its seeded
// disturbance trials under one or two models, per-cell summaries, and the
// bisection of the stability boundary along axis 0. Every function is a pure
// function of the study and its arguments: thread-safe, deterministic, so the
// results never depend on scheduling, thread count or MPI rank count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/map/map_study.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize::map {

/// One trial under one model.
struct TrialOutcome {
  std::string status;        ///< "completed", "fell", "diverged"
  bool stabilized = false;   ///< per MapStudy::stabilized
  long settle_strides = -1;  ///< first stride of the settled tail; -1 never
  long strides = 0;          ///< touchdowns simulated
  double duty_mean = 0.0;    ///< mean stance / stride time [-]
  double peak_force = 0.0;   ///< largest single-leg force [N] (0 for impulses)
};

/// One cell: trials[model][trial], and the stride-map spectral radius of the
/// primary model's undisturbed cell scene (computed by the first cell of each
/// distinct scene only; see stability_owner()). For the pseudo_rigid model the
/// radius is estimated from a few disturbed runs (reduced::estimate_stride_map).
struct CellResult {
  long index = 0;
  std::vector<std::vector<TrialOutcome>> trials;
  bool has_stability = false;
  double spectral_radius = 0.0;  ///< penalty 10 when no periodic orbit
  std::string stability_reason;  ///< why no orbit, if so
};

/// A cell's numbers as written to cells.csv (never NaN).
struct CellSummary {
  long index = 0, row = 0, column = 0;
  double value0 = 0.0, value1 = 0.0;  ///< axis values (value1 = 0 for 1-D maps)
  std::vector<double> fraction;       ///< stabilized fraction per model
  long disagreements = 0;             ///< trials exactly one model stabilizes
  long a_only = 0, b_only = 0;        ///< stabilized by model A only / model B only
  double mean_settle_strides = -1.0;  ///< primary model, over its stabilized trials; -1 none
  double spectral_radius = 0.0;       ///< primary model; 0 when "stability" is off
  double peak_force = 0.0;            ///< primary model, max over trials [N]
  double mean_duty = 0.0;             ///< primary model, mean over trials [-]
  double fell_fraction = 0.0;         ///< primary model
  bool all_stabilized = false;        ///< primary model
};

/// Boundary of one row: the largest axis-0 value at which every trial of the
/// primary model stabilizes — the last cell of the row with all trials
/// stabilized ("last good"), refined by bisection towards the next cell
/// ("first bad" above it) until bad - good <= MapStudy::resolution. Also the
/// lowest such cell (first_good), so a stable band shows both edges.
struct BoundaryResult {
  long row = 0;
  std::string status;     ///< "bisected", "all_good" (no bad cell: boundary >= last value),
                          ///< "none_good" (first cell bad: boundary < first value)
  double boundary = 0.0;  ///< bisected: the good end; all_good: last value; none_good: first value
  double first_good = 0.0;  ///< lowest axis-0 cell value with all trials stabilized (none_good: 0)
  double good = 0.0, bad = 0.0;  ///< final bracket [axis-0 unit]
  long probes = 0;               ///< bisection evaluations (each: N trials)
};

/// Row and column of a cell (index = row * columns + column).
inline long cell_row(const MapStudy& st, long cell) { return cell / st.columns(); }
inline long cell_column(const MapStudy& st, long cell) { return cell % st.columns(); }

/// The undisturbed scene at axis values (v0, v1) (v1 ignored for 1-D maps) with
/// the given model. Throws io::InputError for values that make an invalid scene.
scene::Scene scene_at(const MapStudy& st, double v0, double v1, scene::ModelKind model);

/// The seed key of trials in a cell (row or cell index, per MapStudy::seeding).
std::uint64_t cell_seed_key(const MapStudy& st, long cell);
/// The disturbance of trial `trial` under seed key `key`.
Scenario trial_scenario(const MapStudy& st, std::uint64_t key, long trial);

/// Runs one trial of a scene (disturbance applied) and judges it: the reduced
/// simulator for impulse and pulse, robot::simulate (the scene's "pseudo_rigid"
/// settings) for pseudo_rigid; the same records, metrics and criterion for all.
TrialOutcome run_trial(const MapStudy& st, const scene::Scene& cell_scene, const Scenario& trial);

/// The first cell with the same scene as `cell` (cells differing only in
/// disturbance axes share their stride map): that one computes the spectral radius.
long stability_owner(const MapStudy& st, long cell);

/// Every trial of a cell under every model (serial).
CellResult compute_cell(const MapStudy& st, long cell);

/// Summaries of all cells; spectral radii are copied from the stability owners.
std::vector<CellSummary> summarize(const MapStudy& st, const std::vector<CellResult>& cells);

/// The bracket of a row from its cells; status set, and for "bisected" good/bad
/// set to the last good and the first bad cell value (probes not yet run).
BoundaryResult initial_bracket(const MapStudy& st, const std::vector<CellSummary>& cells, long row);
/// The point the next bisection probe of bracket b (after b.probes probes) tests; false when
/// the bisection has ended (bad - good <= resolution, the step limit, or no representable
/// midpoint).
bool next_probe(const MapStudy& st, const BoundaryResult& b, double* mid);
/// Refines a "bisected" bracket by bisection (serial).
BoundaryResult bisect_row(const MapStudy& st, BoundaryResult bracket);
/// Whether every trial of the primary model stabilizes at axis-0 value v in `row`.
bool all_stabilized_at(const MapStudy& st, long row, double v, long probe);

/// JSON round trips (exact: doubles keep every bit) for the journal and MPI.
nlohmann::json to_json(const CellResult& c);
CellResult cell_from_json(const nlohmann::json& j);
nlohmann::json to_json(const BoundaryResult& b);
BoundaryResult boundary_from_json(const nlohmann::json& j);

}  // namespace pronk::optimize::map
