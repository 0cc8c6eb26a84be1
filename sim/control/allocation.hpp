// Impulse allocation: the middle layer of the control hierarchy (Ridgely 2001, §2.3,
// 2.5.3). Turns the body controller's net linear impulse P and angular impulse
// H (both body frame) into per-leg linear impulses applied at the hips.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace pronk::control {

using Vec3 = Eigen::Vector3d;

/// Which allocation scheme to use.
enum class AllocationScheme {
  /// Ridgely 2001, eq. 2.7-2.8, with the corrected H_y equation: P shared equally among
  /// active legs, moments from per-leg additions Px=c ry, Py=0, Pz=a rx+b ry.
  /// Exact only for layouts symmetric about the CoM (Σrx = Σry = 0 over active legs).
  kSeed,
  /// Minimum-norm per-leg impulses with p_y = 0 (body frame) reproducing (P, H)
  /// exactly, any number/layout of legs; optional per-leg magnitude limits.
  kMinimumNorm,
};

/// A leg's hip position and whether it takes part.
struct LegSlot {
  Vec3 hip_body = Vec3::Zero();  ///< hip position relative to the CoM, body frame [m]
  bool active = true;            ///< false: disabled (failed) or not in this stride's gait
};

struct AllocationOptions {
  AllocationScheme scheme = AllocationScheme::kMinimumNorm;
  /// Per-leg limit on |p_i| [N s]; <= 0 or infinity: no limit (minimum-norm only).
  double max_leg_impulse = 0.0;
  /// Relative residual |(P,H) - produced| / |(P,H)| above which the request is
  /// reported as not producible.
  double residual_tol = 1e-9;
};

enum class AllocationStatus {
  kOk,
  /// The active layout cannot produce the request (e.g. all legs collinear, or
  /// a lateral P_y requested, or a component outside the layout's span). The
  /// per-leg impulses are the least-squares best effort.
  kInfeasible,
  /// Leg limits were active: impulses were scaled/clipped; the residual is reported.
  kLimited,
};

struct AllocationResult {
  AllocationStatus status = AllocationStatus::kOk;
  std::string message;             ///< human-readable reason when status != kOk
  std::vector<Vec3> leg_impulse;   ///< per leg (inactive legs get zero), body frame [N s]
  Vec3 produced_P = Vec3::Zero();  ///< Σ p_i [N s]
  Vec3 produced_H = Vec3::Zero();  ///< Σ r_i × p_i [N m s]
  double relative_residual = 0.0;  ///< |(P,H) - produced| / max(|(P,H)|, tiny)
};

/// Allocates (P, H) [N s, N m s], body frame, among the legs. Pure function:
/// no allocation-dependent state, thread-safe.
AllocationResult allocate(const std::vector<LegSlot>& legs, const Vec3& P, const Vec3& H,
                          const AllocationOptions& options);

}  // namespace pronk::control
