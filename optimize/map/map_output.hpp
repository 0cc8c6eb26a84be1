// The result files of a robustness map: CSV tables, summary.json and the
// gnuplot heat maps (fraction stabilized; disagreement) with the boundary
// drawn. Pure functions of the study and its results, so the bytes do not
// depend on how the map was computed (threads, ranks, resumed or not).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/map/map_engine.hpp"

namespace pronk::optimize::map {

/// Shortest decimal that reads back to the same double.
std::string format_number(double v);

std::string cells_csv(const MapStudy& st, const std::vector<CellSummary>& cells);
std::string trials_csv(const MapStudy& st, const std::vector<CellResult>& cells);
std::string boundary_csv(const MapStudy& st, const std::vector<CellSummary>& cells,
                         const std::vector<BoundaryResult>& boundaries);
nlohmann::json summary_json(const MapStudy& st, const std::vector<CellSummary>& cells,
                            const std::vector<BoundaryResult>& boundaries);

/// Lowest axis-0 value of a row with a disagreement; < 0 index when none.
long first_disagreement_column(const MapStudy& st, const std::vector<CellSummary>& cells, long row);

/// The gnuplot datablock $boundary of a heat map: per row with a good cell, the boundary, the
/// row's value and the lowest good cell; a blank line at a "none_good" row, so that gnuplot
/// breaks the line there (as report.html does).
struct BoundaryBlock {
  std::string text;   ///< "# ...\n$boundary << EOD\n...EOD\n"
  bool any = false;   ///< some row has a boundary
  bool band = false;  ///< some row's lowest good cell is above the axis' first value
};
BoundaryBlock boundary_block(const MapStudy& st, const std::vector<BoundaryResult>& boundaries);

/// The gnuplot script of a heat map: "fraction" (primary model's fraction
/// stabilized) or "disagreement" (fraction of trials the two models disagree on).
std::string heatmap_script(const MapStudy& st, const std::vector<CellSummary>& cells,
                           const std::vector<BoundaryResult>& boundaries, const std::string& what);

}  // namespace pronk::optimize::map
