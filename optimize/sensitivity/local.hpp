// Local sensitivities: the derivative of every output with respect to every input at one point,
// by central differences at steps h and h/2 combined by Richardson extrapolation,
//   D(h) = (f(x + h e_j) - f(x - h e_j)) / 2h,   D = (4 D(h/2) - D(h)) / 3,
// with the error estimate |D(h/2) - D(h)| / 3 (the leading error term of D(h/2), a bound on
// the extrapolated value's for smooth f) plus the rounding error of the differences. The
// elasticity (x / f) df/dx is the relative change of the output per relative change of the
// input.
#pragma once

#include <string>
#include <vector>

#include "optimize/sensitivity/batch_function.hpp"

namespace pronk::optimize::sensitivity {

struct LocalOptions {
  /// The step h of input j: step * |x_j|, or step itself when x_j == 0 (relative).
  double step = 1e-2;
  /// Throws io::InputError (naming "--local-step") unless 0 < step < 1.
  void validate() const;
};

struct LocalResult {
  std::vector<double> x0;  ///< the point
  std::vector<double> h;   ///< the largest step of each input (the differences use h and h/2)
  std::vector<double> f0;  ///< the outputs at x0
  /// [output][input]: the extrapolated derivative, its error estimate and the elasticity
  /// (NaN when f0 is 0 and the derivative is not).
  std::vector<std::vector<double>> derivative, error, elasticity;
  long evaluations = 0;  ///< 4 per input, plus 1
};

/// The points local_sensitivity evaluates, in its order: x0, then per input j
/// x0 + h e_j, x0 - h e_j, x0 + h/2 e_j, x0 - h/2 e_j.
std::vector<Point> local_points(const std::vector<double>& x0, const LocalOptions& options);

/// Local sensitivities of `f` at `x0` (one batch of local_points).
LocalResult local_sensitivity(const BatchFunction& f, const std::vector<double>& x0,
                              const LocalOptions& options);

/// The same from the outputs of local_points(x0, options), in their order.
LocalResult local_from_outputs(const std::vector<double>& x0, const LocalOptions& options,
                               const std::vector<std::vector<double>>& outputs);

}  // namespace pronk::optimize::sensitivity
