// Attitude representations: unit quaternions (the internal form), rotation
// matrices and Euler angles (input/output only) for the 1-2-3 and 3-1-3 sets.
//
// Conventions: a rotation R maps body-frame vectors to the world frame,
// v_world = R v_body. Quaternions are Eigen::Quaterniond (w, x, y, z), unit norm.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pronk::math {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// Euler-angle sets. Angles [rad] are (a1, a2, a3) about the listed axes.
enum class EulerSet {
  /// 1-2-3 (roll-pitch-yaw about body x, then body y, then body z; intrinsic):
  /// R = Rx(a1) Ry(a2) Rz(a3). Gimbal lock at a2 = ±pi/2.
  k123,
  /// 3-1-3 (z-x-z intrinsic: psi, theta, phi): R = Rz(a1) Rx(a2) Rz(a3).
  /// Gimbal lock at a2 = 0 or pi.
  k313,
};

/// Rotation matrix of the Euler angles (exact, any angles).
Mat3 euler_to_matrix(const Vec3& angles, EulerSet set);
/// Quaternion of the Euler angles (unit, w >= 0 not required).
Quat euler_to_quat(const Vec3& angles, EulerSet set);
/// Euler angles of a rotation matrix. a1, a3 in (-pi, pi]; a2 in [-pi/2, pi/2]
/// for 1-2-3 and [0, pi] for 3-1-3. At gimbal lock (within 1e-12 of the
/// singular a2) all of the rotation about the coupled axis is put into the first
/// angle and the third is 0 (Ridgely 2001, §3.4.5). Never NaN for a finite proper rotation
/// (entries slightly outside [-1,1] by rounding are harmless: only atan2 of
/// consistent pairs is used, no asin/acos). Lock test: |cos a2| (1-2-3) or
/// |sin a2| (3-1-3) below 1e-12.
Vec3 matrix_to_euler(const Mat3& R, EulerSet set);
Vec3 quat_to_euler(const Quat& q, EulerSet set);

/// Time derivative of the attitude quaternion for body angular velocity w_body
/// [rad/s]: dq/dt = 1/2 q ⊗ (0, w_body). Returned as (w, x, y, z) coefficients.
Eigen::Vector4d quat_derivative(const Quat& q, const Vec3& w_body);

/// Rates of the Euler angles given body angular velocity [rad/s] for the 1-2-3
/// set (exact kinematics; singular at gimbal lock, where it returns the
/// small-angle value w_body itself, when |cos a2| < 1e-9, instead of dividing
/// by ~0). Returns (a1', a2', a3') [rad/s].
Vec3 euler123_rates(const Vec3& angles, const Vec3& w_body);

/// Angular velocity [rad/s] of a body whose Euler angles [rad] change at the
/// given rates [rad/s], expressed in the world frame. For 1-2-3:
/// w = a1' x + a2' Rx(a1) y + a3' Rx(a1) Ry(a2) z; for 3-1-3:
/// w = a1' z + a2' Rz(a1) x + a3' Rz(a1) Rx(a2) z. Exact for any angles.
Vec3 euler_rates_to_world_omega(const Vec3& angles, const Vec3& rates, EulerSet set);
/// Same angular velocity expressed in the body frame (R^T times the world value).
Vec3 euler_rates_to_body_omega(const Vec3& angles, const Vec3& rates, EulerSet set);

/// Rotation vector (axis * angle [rad], angle in [0, pi]) of a quaternion; the
/// attitude error used by controllers for large angles. q and -q give the same
/// (shortest) result; q need not be exactly unit (the result is scale-invariant).
Vec3 quat_to_rotation_vector(const Quat& q);

/// Normalises q; returns identity if q is not finite or has ~zero norm
/// (below 1e-100; the norm is computed with scaling, so no overflow).
Quat normalized_or_identity(const Quat& q);

}  // namespace pronk::math
