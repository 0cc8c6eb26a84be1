// Leg placement in flight: the leg directions for the predicted touchdown (legs parallel to the
// impulse, or free stance hips put by the neutral-point rule).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "sim/control/stance_planner.hpp"

namespace pronk::robot::detail {

using Eigen::Vector3d;

/// Leg placement for the predicted touchdown: every leg parallel to the net linear
/// impulse the legs must deliver (body frame, no body-y part), within max_angle of
/// -z, so the spring rebound pushes where the impulse must go without adding a
/// moment of its own; the moments are left to the actuators. Unit directions hip -> foot.
std::vector<Vector3d> leg_directions(const control::StancePlan& plan, size_t legs,
                                     double max_angle);

/// Leg placement for free stance hips (world frame, unit hip -> foot): the leg,
/// a strut from hip to foot during the stance, pushes along its mean direction,
/// so the foot is put where the mean foot -> hip line over the stance is parallel
/// to the net impulse the ground must give, P = P_legs + m g T_s (world [N s]):
/// half the stance's horizontal travel ahead of that, v T_s / 2 (Raibert's
/// neutral point, corrected by the impulse's tilt). v: horizontal CoM velocity
/// at touchdown [m/s]; stance: expected stance duration T_s [s]; leg: leg length
/// [m]; max_angle: limit from the vertical [rad].
/// held_roll: with the stance roll held (stance attitude feedback) the body moves
/// over its gripped feet only along the legs in the lateral plane (ab/adduction is
/// held too), so the lateral velocity across the legs is lost at touchdown and the
/// takeoff velocity follows the legs: the leg is put along the desired takeoff
/// velocity v_takeoff across the body instead (no neutral point); heading: the body x axis's
/// angle from the world's x axis at touchdown [rad].
Vector3d free_leg_direction(const Vector3d& P, const Vector3d& v, double stance, double leg,
                            double max_angle, bool held_roll, const Vector3d& v_takeoff,
                            double heading = 0.0);

/// The same placement with the stance's horizontal motion solved as an inverted pendulum
/// over the foot: with the mean vertical ground force F = P_z / T_s on the leg height h, the
/// hip's horizontal offset x from its foot obeys x'' = w^2 x, w^2 = F / (m h), so the stance
/// gives P_h = m (w sinh(wT) x0 + (cosh(wT) - 1) v0) for an offset x0 and speed v0 at
/// touchdown; the foot goes at -x0 for the P_h asked. For small wT it is free_leg_direction's
/// rule with v0 for the mean speed (r = T v0 / 2 - h P_h / P_z); pr_running's stances have
/// wT ~ 1.3-1.7, where the linear rule's foot is several mm too far forward.
Vector3d pendulum_leg_direction(const Vector3d& P, const Vector3d& v0, double stance, double leg,
                                double mass, double max_angle, bool held_roll,
                                const Vector3d& v_takeoff, double heading = 0.0);

/// The legs turned apart for a yaw impulse: the common leg d (world, unit hip -> foot) with
/// each foot moved across its hip's lever from the hips' centre so that the legs' horizontal
/// pushes add up to Hz about the vertical [N m s] and to nothing in translation: a leg that
/// carries Pz / n of the stance's vertical impulse [N s] pushes -Pz r / (n leg) sideways for
/// its foot moved by r. hips: the hips' horizontal positions (world axes) [m]; each foot stays
/// within max_angle of the vertical. Unit directions hip -> foot, world axes.
std::vector<Vector3d> yaw_leg_directions(const Vector3d& d,
                                         const std::vector<Eigen::Vector2d>& hips, double Hz,
                                         double Pz, double leg, double max_angle);

/// How the horizontal impulse a placed leg delivers answers a change of the impulse it was
/// placed for, linearised: the foot moved by -leg dP / |P| changes the impulse by dP / (1 - c),
/// c = T_s |P| / (4 m leg), because the CoM's own speed-up moves it further over the foot
/// (the neutral point's feedback on itself). Returns 1 - c, kept within [0.1, 1] [-].
double free_leg_response(const Vector3d& P, double stance, double leg, double mass);

}  // namespace pronk::robot::detail
