// The Jacobian df/dy of an ODE system by forward differences of its RHS, for systems
// without an analytic one (a mechanism with a rigid body: its quaternion kinematics).
#pragma once

#include <Eigen/SparseCore>

#include "sim/ode/ode_system.hpp"

namespace pronk::ode {

/// Forward differences, step sqrt(eps) (1 + |y_i|) per column (n + 1 RHS evaluations; ~1e-8
/// relative, far below what the stiff steppers need); entries that difference to exactly zero
/// are left out of the sparse J (n x n).
void difference_jacobian(const OdeSystem& sys, double t, const Vec& y,
                         Eigen::SparseMatrix<double>& J);

}  // namespace pronk::ode
