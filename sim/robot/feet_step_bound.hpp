// The step bound that quasi-static feet leave for method verlet (docs/notes/quasi_static_feet.md).
//
// With massless feet the stiffest mode is no longer a foot on its slide and the ground
// (1 g on 1e5 N/m: ~1e4 rad/s) but the rigid body on its landed legs: each pinned foot holds
// the body through its slot spring (k_s along the slot normal n at the foot, the plane through
// the hip that holds the leg and the body x axis) and its leg spring (k along the leg at the
// hip). The friction creep in series is a damper that does not yield on the body's time scale
// (k_s v_s / (mu N) ~ 25 1/s), so it counts as rigid. Linearised about a stance with every foot
// down, the body's 6 x 6 stiffness is K = sum k J^T J with J = [u^T, (p x u)^T] (u the
// spring's direction, p its point on the body from the CoM), its mass matrix diag(M, M, M, I),
// and verlet is stable for h < 2 / omega_max, omega_max^2 the largest eigenvalue of
// K v = omega^2 M v. More feet only stiffen K (its largest eigenvalue is monotone), so all feet
// down bounds every stance. The geometry turns with the placement: the bound is the largest
// omega over the legs' rest lengths 0.75 .. 1.25 of nominal (level_feet's range) and the legs
// turned fore-aft and sideways by up to max_leg_angle (all legs alike). A locked stance hip
// holds its foot on the leg's line: two slot springs, across the leg, at the foot. On the
// four-mass body
// the same springs load the masses (the hip's barycentric weights; the slot's turning normal
// through the fitted attitude's derivative) beside the six body springs: a 12 x 12 problem.
#pragma once

#include <array>
#include <string>

#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::robot {

/// The slot normals (body frame, unit; zero when absent) that hold a landed quasi-static foot
/// of a leg along body-frame unit direction dir (hip -> foot): a free hip's slot is the plane
/// of the leg and the body x axis (normal dir x x; none for a leg along x), a locked hip's the
/// leg's line (two normals across it).
std::array<Eigen::Vector3d, 2> slot_normals(const Eigen::Vector3d& dir, bool locked);

/// omega_max of the body on quasi-static feet [rad/s] (see the file comment); 0 for a model
/// without them.
double quasi_static_omega(const scene::Scene& s, const RobotModel& m);

/// omega_max for one stance: every leg of length `rest_scale` x its nominal rest length along
/// the body-frame unit direction `dir` (hip -> foot).
double quasi_static_omega(const scene::Scene& s, const RobotModel& m, double rest_scale,
                          const Eigen::Vector3d& dir);

}  // namespace pronk::robot
