// A leg of the MuJoCo robot as joint coordinates (sim/mujoco/robot_mjcf.hpp): at its hip a roll
// hinge about the body x axis, then a pitch hinge about the rolled y axis, then a slide along
// the leg, so the leg's direction (body frame, hip -> foot) is
//   d(roll, pitch) = R_x(roll) R_y(pitch) (0, 0, -1) = (-sin p, cos p sin r, -cos p cos r)
// and the foot sits at hip + (length + slide) d. The pseudo-rigid robot's slot (a landed foot
// held in the plane of its leg and the body x axis, free about the plane's normal) is the roll
// hinge held and the pitch hinge free. Pure kinematics, no MuJoCo: the map between the
// joints and the foot that the engine's stepper uses both ways.
#pragma once

#include <Eigen/Dense>

namespace pronk::mujoco {

/// One leg's joint coordinates and rates.
struct LegJoints {
  double roll = 0.0, pitch = 0.0, slide = 0.0;                 ///< [rad, rad, m]
  double roll_rate = 0.0, pitch_rate = 0.0, slide_rate = 0.0;  ///< [rad/s, rad/s, m/s]
};

/// The unit leg direction d(roll, pitch), body frame, hip -> foot.
Eigen::Vector3d leg_direction(double roll, double pitch);

/// The hinge angles of a unit body-frame direction d (hip -> foot): pitch = asin(-d_x),
/// roll = atan2(d_y, -d_z). Writes roll and pitch.
void leg_angles(const Eigen::Vector3d& d, double* roll, double* pitch);

/// The joints of a leg whose foot is at `r` from its hip, moving at `r_rate` relative to the
/// hip, both in body axes [m, m/s] (the rate as seen in the body frame); `length`: the leg
/// length at slide 0 [m].
LegJoints leg_joints(const Eigen::Vector3d& r, const Eigen::Vector3d& r_rate, double length);

/// The foot's offset from its hip (body axes) [m] and its rate seen in the body frame [m/s].
void foot_offset(const LegJoints& q, double length, Eigen::Vector3d* r, Eigen::Vector3d* r_rate);

}  // namespace pronk::mujoco
