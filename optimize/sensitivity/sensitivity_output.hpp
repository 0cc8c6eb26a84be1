// The result files of `pronk sensitivity`, written atomically into one directory:
//   sensitivity.json  everything (inputs, outputs, local derivatives, one-at-a-time ends,
//                     Sobol indices with their intervals; NaN as null)
//   local.csv         output, input, derivative, error, elasticity
//   sobol.csv         output, input, S1, S1_lo, S1_hi, ST, ST_lo, ST_hi
//   tornado.csv       output, input, value, lower, upper, f0, f_lower, f_upper
//   tornado.svg       the charted output with each input at the ends of its range
//   sobol.svg         the charted output's first-order and total indices with intervals
//   summary.md        the tables of the charted output, and each output's strongest input
//   report.html       summary.md as a static page with the two figures
#pragma once

#include <string>

#include "optimize/sensitivity/design_sensitivity.hpp"

namespace pronk::optimize::sensitivity {

/// Writes the files into `dir` (created). `chart` names the output the charts show (one of
/// s.outputs). Throws std::runtime_error on I/O failure; a missing gnuplot only leaves the
/// .gp scripts (io::FigureBatch).
void write_sensitivity(const DesignSensitivity& s, const std::string& dir,
                       const std::string& chart);

/// The index of output `name` in s.outputs; throws io::InputError (naming "--chart") when
/// there is none.
size_t chart_output(const DesignSensitivity& s, const std::string& name);

}  // namespace pronk::optimize::sensitivity
