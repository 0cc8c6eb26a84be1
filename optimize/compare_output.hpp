// The outputs of a comparison (optimize/compare.hpp): each design's playback run of the same
// trial (runs/<label>/ with its view.html, by the run-output code of `pronk simulate`) and
// the comparison's own files (io/write/comparison_output.hpp: compare.csv, trials.csv,
// summary.md, compare.json). The page (report.html) is io/page's, from these files.
#pragma once

#include <string>

#include "io/write/comparison_output.hpp"
#include "optimize/compare.hpp"

namespace pronk::optimize {

/// Throws io::InputError (naming "--out") when `dir` holds another command's results (a
/// study, a map or a run): the comparison's summary.md and report.html would replace theirs.
void check_comparison_directory(const std::string& dir);

/// The comparison as the files show it (each design's run directory runs/<label>).
io::ComparisonData comparison_data(const Comparison& c);

/// Writes every design's playback run and the comparison's files into `dir` (created);
/// returns what was written. A design whose parameters make no valid scene in its model
/// has no run (the summary says why).
io::ComparisonData write_comparison(const std::string& dir, const Comparison& c);

}  // namespace pronk::optimize
