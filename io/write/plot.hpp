// Figures: a gnuplot script written beside the data and rendered to SVG. The
// data (CSV) is the primary result; a missing gnuplot is reported once per
// process and is not fatal. FigureBatch (figure_batch.hpp) renders the figures of
// an output directory together; this file renders one.
#pragma once

#include <string>

namespace pronk::io {

/// Whether figures are rendered (the default) or only their scripts written (the command
/// line's --no-figures: the CSV data and every .gp script are still written, and `gnuplot
/// NAME.gp` in the run's directory renders one later). Process-wide: set by the command line
/// before any output.
void set_render_figures(bool render);
bool render_figures();

/// True when a gnuplot executable is on PATH (checked once).
bool gnuplot_available();

/// Says on stderr, once per process, that gnuplot is missing and the figures not rendered.
void report_missing_gnuplot();

/// The script of figure `name` (which must hold `set output 'NAME.svg'`) with its output sent
/// to standard output instead; std::logic_error when it does not set that output.
std::string script_to_stdout(const std::string& name, const std::string& script);

/// Runs gnuplot in `dir` on `stdout_script` (from script_to_stdout) and writes its SVG to
/// `dir/name.svg` atomically: true. False when gnuplot fails or its output is not a whole SVG
/// document: then `dir/name.svg` is removed (no figure rather than one of an earlier run).
/// Throws std::runtime_error when the process or the file cannot be made. Safe to call from
/// several threads at once.
bool render_svg(const std::string& dir, const std::string& name, const std::string& stdout_script);

}  // namespace pronk::io
