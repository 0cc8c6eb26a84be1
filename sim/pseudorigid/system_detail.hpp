// What the files of MechanismSystem's implementation (system*.cpp) share; no other file
// includes it.
#pragma once

#include <Eigen/Core>

#include "sim/ode/ode_system.hpp"

namespace pronk::pseudorigid {
namespace detail {

/// The 3-vector of y at index i: a mass's position (6 j) or momentum (6 j + 3), a rigid
/// body's angular momentum (r + 4).
inline Eigen::Vector3d seg(const ode::Vec& y, int i) { return y.segment<3>(i); }

}  // namespace detail

// The names every file of the implementation uses.
using detail::seg;
using Eigen::Matrix3d;
using Eigen::Vector3d;

}  // namespace pronk::pseudorigid
