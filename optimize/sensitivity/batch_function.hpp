// The pure-function interface of the sensitivity numerics (local.hpp, sobol.hpp): a model
// evaluated on a batch of points, each point a vector of inputs, each answer a vector of
// outputs (the same count for every point). The numerics never see the physics, so they are
// testable on analytic functions; the caller decides how a batch runs (threads, MPI ranks).
#pragma once

#include <functional>
#include <vector>

namespace pronk::optimize::sensitivity {

using Point = std::vector<double>;
/// f(points)[i] = the outputs at points[i]. Must be a pure function of each point.
using BatchFunction = std::function<std::vector<std::vector<double>>(const std::vector<Point>&)>;

}  // namespace pronk::optimize::sensitivity
