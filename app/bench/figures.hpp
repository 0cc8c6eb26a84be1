// The diagrams of `pronk bench`.
#pragma once

#include <string>

#include "app/bench/report.hpp"

namespace pronk::app::bench {

/// Writes the SVG diagrams and their gnuplot scripts of r into dir (io::FigureBatch).
void write_bench_figures(const std::string& dir, const BenchResults& r);

}  // namespace pronk::app::bench
