// Global sensitivities: first-order and total Sobol indices of every output over a box of
// inputs, each uniform in [lower, upper], by Saltelli sampling.
//
// Two N x k matrices A and B of independent uniform draws (a seeded SplitMix64 stream per row:
// row i depends only on (seed, i)), and for every input j the matrix AB_j, A with column j
// taken from B: N (k + 2) evaluations. With V the variance of f over the rows of A and B,
//   first order (Saltelli et al. 2010):  S_j  = mean(f(B) (f(AB_j) - f(A))) / V
//   total effect (Jansen 1999):          ST_j = mean((f(A) - f(AB_j))^2) / 2V
// Confidence intervals: percentile bootstrap over the N rows (seeded resampling).
#pragma once

#include <cstdint>
#include <vector>

#include "optimize/sensitivity/batch_function.hpp"

namespace pronk::optimize::sensitivity {

struct SobolOptions {
  long samples = 32;         ///< N, the rows of A and B (N (k + 2) evaluations)
  long bootstrap = 200;      ///< bootstrap resamples for the confidence intervals
  double confidence = 0.95;  ///< of the intervals
  std::uint64_t seed = 1;
  /// Throws io::InputError (naming "--samples" and so on) for N < 2, bootstrap < 10, or a
  /// confidence outside (0, 1).
  void validate() const;
};

/// The indices of one output.
struct SobolIndices {
  double mean = 0.0, variance = 0.0;  ///< of the output over A and B
  /// Per input; NaN when the output does not vary (V == 0) or is not finite somewhere.
  std::vector<double> s1, s1_lo, s1_hi, st, st_lo, st_hi;
};

struct SobolResult {
  std::vector<SobolIndices> outputs;
  long evaluations = 0;
};

/// The N (k + 2) points of the design, in the order A, B, AB_0, ..., AB_{k-1} (N rows each).
std::vector<Point> saltelli_points(const std::vector<double>& lower,
                                   const std::vector<double>& upper, const SobolOptions& options);

/// The indices from the outputs of saltelli_points (same order; k inputs).
SobolResult sobol_from_outputs(size_t inputs, const SobolOptions& options,
                               const std::vector<std::vector<double>>& outputs);

/// saltelli_points, one batch of f, sobol_from_outputs.
SobolResult sobol_indices(const BatchFunction& f, const std::vector<double>& lower,
                          const std::vector<double>& upper, const SobolOptions& options);

}  // namespace pronk::optimize::sensitivity
