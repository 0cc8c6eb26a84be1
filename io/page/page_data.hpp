// The data of a page, read back from a directory that pronk wrote: a robot run
// (trajectory.csv, strides.csv, optional feet.csv and energy.csv of the full model), a
// mechanism run (nodes.csv, bodies.csv, energy.csv), a study (history.csv, design.json,
// initial/ and tuned/ runs), a staged study (stages/*/) or a map (cells.csv, boundary.csv,
// summary.json, playback.json), a comparison of designs (compare.json, compare.csv,
// trials.csv, runs/*/) or a multi-objective study (pareto.json, journal.jsonl, front/*/).
// Missing or damaged files are InputErrors naming the file.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace pronk::io::page {

enum class DirKind { kRobotRun, kMechanismRun, kStudy, kStagedStudy, kMap, kComparison, kPareto };

/// What `dir` holds. InputError when it is not a directory or holds none of the above.
DirKind classify_directory(const std::string& dir);

/// "view" for runs, "report" for studies and maps: the template and file name of its page.
std::string page_name(DirKind kind);

/// Numbers a run page holds at most: a 100 s run sampled at 0.01 s (10^4 rows of 19
/// columns) keeps every sample and the page stays under 5 MB.
inline constexpr long kRunPageCells = 300000;

/// The page data of a run directory (robot or mechanism), at most `max_cells` numbers
/// per table.
nlohmann::json run_page_data(const std::string& dir, long max_cells = kRunPageCells);

/// The page data of a comparison directory (`pronk compare`): its designs, metrics and
/// trials, and every design's playback run.
nlohmann::json comparison_page_data(const std::string& dir);

/// The page data of a multi-objective study directory (pareto.json, journal.jsonl, and each
/// front design's playback run front/<k>/ when written).
nlohmann::json pareto_page_data(const std::string& dir);

/// The page data of any directory classify_directory() accepts.
nlohmann::json page_data(const std::string& dir, DirKind kind);

}  // namespace pronk::io::page

namespace pronk::io::page {

/// Writes the page of `dir` (view.html for a run, report.html for a study or map) from
/// its files, atomically. Returns the page's path, or "" (nothing written) when the
/// templates are absent (missing_template_hint() says how to get them).
std::string write_directory_page(const std::string& dir);

}  // namespace pronk::io::page
