// The rigid body (BodySpec::rigid): the body of a mechanism as ONE rigid body instead of
// four masses held by six springs, for scenes that do not study the body's flexibility.
// Newton-Euler with the same mass and inertia tensor: its translation is one mass at the
// CoM (a regular mass of the state), its rotation 7 states after all masses' (model.hpp):
// the attitude quaternion q (body to world, w x y z) and the world angular momentum L, so
// torques kick L as forces kick momenta (dL/dt = tau, dq/dt = 1/2 (0, omega) q with
// omega = R I^-1 R^T L). q is normalised wherever it is read; ghost points are body-fixed
// points x_c + R r, forces at them act on the CoM mass plus a torque r x F.
//
// Method verlet: the drift of the rotation is the free rigid body's flow at fixed L,
// approximated by the symmetric splitting of its kinetic energy over the principal axes
// (Dullweber, Leimkuhler, McLachlan 1997: rotations about axes 1, 2 by h/2, axis 3 by h,
// axes 2, 1 by h/2, each exact), so kick-drift-kick stays symplectic and time-reversible,
// |q| = 1 and |L| are kept to round-off, and the energy error stays bounded.
#pragma once

#include <Eigen/Dense>

#include "sim/ode/ode_system.hpp"
#include "sim/pseudorigid/body.hpp"

namespace pronk::pseudorigid {

/// The unit quaternion of the rigid body whose rotation states start at y[r].
inline Eigen::Quaterniond rigid_quaternion(const ode::Vec& y, int r) {
  return Eigen::Quaterniond(y[r], y[r + 1], y[r + 2], y[r + 3]).normalized();
}

/// Body-to-world rotation at y (states at r).
inline Eigen::Matrix3d rigid_rotation(const ode::Vec& y, int r) {
  return rigid_quaternion(y, r).toRotationMatrix();
}

/// World inverse inertia R I^-1 R^T [1/(kg m^2)].
inline Eigen::Matrix3d rigid_inverse_inertia(const Body& b, const Eigen::Matrix3d& rot) {
  return rot * b.inverse_inertia * rot.transpose();
}

/// World angular velocity omega = R I^-1 R^T L [rad/s].
inline Eigen::Vector3d rigid_omega(const Body& b, const Eigen::Matrix3d& rot,
                                   const Eigen::Vector3d& L) {
  return rot * (b.inverse_inertia * (rot.transpose() * L));
}

/// dq/dt = 1/2 (0, omega) q for the (unnormalised) quaternion at y[r] into dydt[r..r+3].
void rigid_quaternion_rate(const ode::Vec& y, int r, const Eigen::Vector3d& omega, ode::Vec& dydt);

/// Method verlet's drift of the rotation over h [s] at fixed L (see the file comment):
/// updates the quaternion y[r..r+3] (normalised on return).
/// `rotation`: rigid_rotation(y, r), when the caller has it (else computed here).
void rigid_rotation_drift(const Body& b, double h, ode::Vec& y, int r,
                          const Eigen::Matrix3d* rotation = nullptr);

/// Principal moments and axes (columns, a proper rotation) of the body's inertia tensor.
void principal_axes(const Eigen::Matrix3d& inertia, Eigen::Vector3d* moments,
                    Eigen::Matrix3d* axes);

}  // namespace pronk::pseudorigid
