// Figures: a gnuplot script written beside the data and rendered to SVG. The
// data (CSV) is the primary result; a missing gnuplot is reported once per
// process and is not fatal.
#pragma once

#include <string>

namespace pronk::io {

/// Writes `dir/name.gp` (the script, which must write `name.svg` when run in `dir`)
/// and runs gnuplot on it in `dir`. Returns false (after one message to stderr per
/// process) when gnuplot is unavailable or fails; the script stays for the user.
bool render_figure(const std::string& dir, const std::string& name, const std::string& script);

/// Whether render_figure runs gnuplot (the default) or writes only the scripts (the command
/// line's --no-figures: the CSV data and every .gp script are still written, and `gnuplot
/// NAME.gp` in the run's directory renders one later). Process-wide: set by the command line
/// before any output.
void set_render_figures(bool render);

/// True when a gnuplot executable is on PATH (checked once).
bool gnuplot_available();

}  // namespace pronk::io
