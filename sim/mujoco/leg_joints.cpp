#include "sim/mujoco/leg_joints.hpp"

#include <algorithm>
#include <cmath>

namespace pronk::mujoco {

using Eigen::Vector3d;

Vector3d leg_direction(double roll, double pitch) {
  const double sp = std::sin(pitch), cp = std::cos(pitch);
  return {-sp, cp * std::sin(roll), -cp * std::cos(roll)};
}

void leg_angles(const Vector3d& d, double* roll, double* pitch) {
  *pitch = std::asin(std::clamp(-d.x(), -1.0, 1.0));
  *roll = std::atan2(d.y(), -d.z());
}

namespace {
/// d's partial derivatives by roll and pitch: with d itself an orthogonal frame whose roll
/// column has length cos(pitch) and whose pitch column has length 1.
void partials(double roll, double pitch, Vector3d* d_roll, Vector3d* d_pitch) {
  const double sp = std::sin(pitch), cp = std::cos(pitch);
  const double sr = std::sin(roll), cr = std::cos(roll);
  *d_roll = Vector3d(0.0, cp * cr, cp * sr);
  *d_pitch = Vector3d(-cp, -sp * sr, sp * cr);
}
}  // namespace

LegJoints leg_joints(const Vector3d& r, const Vector3d& r_rate, double length) {
  LegJoints q;
  const double l = r.norm();
  leg_angles(r / l, &q.roll, &q.pitch);
  q.slide = l - length;
  Vector3d d_roll, d_pitch;
  partials(q.roll, q.pitch, &d_roll, &d_pitch);
  // r_rate = l' d + l (d_roll roll' + d_pitch pitch'), the three columns orthogonal.
  q.slide_rate = r_rate.dot(r / l);
  const double c2 = d_roll.squaredNorm();
  q.roll_rate = c2 > 0.0 ? r_rate.dot(d_roll) / (l * c2) : 0.0;
  q.pitch_rate = r_rate.dot(d_pitch) / l;
  return q;
}

void foot_offset(const LegJoints& q, double length, Vector3d* r, Vector3d* r_rate) {
  const Vector3d d = leg_direction(q.roll, q.pitch);
  const double l = length + q.slide;
  Vector3d d_roll, d_pitch;
  partials(q.roll, q.pitch, &d_roll, &d_pitch);
  *r = l * d;
  *r_rate = q.slide_rate * d + l * (d_roll * q.roll_rate + d_pitch * q.pitch_rate);
}

}  // namespace pronk::mujoco
