// The Jacobian df/dy of an ODE system by central differences of its RHS, for systems
// without an analytic one (a mechanism with a rigid body: its quaternion kinematics).
#pragma once

#include <Eigen/SparseCore>

#include "sim/ode/ode_system.hpp"

namespace pronk::ode {

/// Central differences, step sqrt-ish 1e-7 (1 + |y_i|) per column (2n RHS evaluations);
/// entries that difference to exactly zero are left out of the sparse J (n x n).
void difference_jacobian(const OdeSystem& sys, double t, const Vec& y,
                         Eigen::SparseMatrix<double>& J);

}  // namespace pronk::ode
