#include "sim/control/body_controller.hpp"

#include <algorithm>
#include <cmath>

#include "sim/math/rotation.hpp"

namespace pronk::control {

using Eigen::Vector3d;

PdBodyController::PdBodyController(const scene::Controller& config, double gravity,
                                   double leg_length, bool legged, bool small_angle,
                                   double stance_duration)
    : config_(config),
      takeoff_speed_(std::sqrt(2.0 * gravity * config.hop_height)),
      gravity_(gravity),
      stance_duration_(config.pulse_aware_hop ? stance_duration : 0.0),
      leg_length_(leg_length),
      bank_(legged && config.bank_enabled),
      small_angle_(small_angle) {}

BodyCommand PdBodyController::command(double t, const BodyState& s) const {
  const auto& kp = config_.kp;
  const auto& kd = config_.kd;
  const Vector3d x_d = config_.setpoint_position + config_.setpoint_velocity * t;
  const Vector3d v_d = config_.setpoint_velocity;
  BodyCommand c;
  const Vector3d e = x_d - s.position;
  const Vector3d ev = v_d - s.velocity;
  c.P_world.x() = kp[0] * e.x() + kd[0] * ev.x();
  c.P_world.y() = kp[1] * e.y() + kd[1] * ev.y();
  // Hop-height law (Ridgely 2001, §2.4.1): Kd_z = m and setpoint sqrt(2 g h) make the next
  // apex exactly h above the touchdown height.
  double v1 = takeoff_speed_;
  if (stance_duration_ > 0.0) {
    // Constant force over T: the CoM moves (v0 + v1) T / 2 during the stance, so
    // the apex is l + (v0 + v1) T / 2 + v1^2 / (2 g); solve for v1 >= 0.
    const double T = stance_duration_, g = gravity_, v0 = s.velocity.z();
    const double half = 0.5 * g * T;
    v1 = -half +
         std::sqrt(std::max(half * half + 2.0 * g * config_.hop_height - g * v0 * T, half * half));
  }
  c.P_world.z() = kp[2] * (leg_length_ - s.position.z()) + kd[2] * (v1 - s.velocity.z());

  // Desired attitude: level at the setpoint heading; banking turns the lateral
  // error (in the heading frame) into a roll: legs push along body z, so a
  // negative roll tilts their push towards +y.
  const double yaw = config_.setpoint_yaw;
  double roll_d = 0.0;
  if (bank_) {
    const double e_lat = -std::sin(yaw) * e.x() + std::cos(yaw) * e.y();
    const double ev_lat = -std::sin(yaw) * ev.x() + std::cos(yaw) * ev.y();
    roll_d = -std::clamp(config_.bank_kp * e_lat + config_.bank_kd * ev_lat, -config_.bank_max_roll,
                         config_.bank_max_roll);
  }
  c.desired_euler123 = Vector3d(roll_d, 0.0, yaw);
  Vector3d e_att;
  if (small_angle_) {
    e_att = c.desired_euler123 - s.euler123;
  } else {
    const math::Quat q_d = math::euler_to_quat(c.desired_euler123, math::EulerSet::k123);
    e_att = math::quat_to_rotation_vector(s.attitude.conjugate() * q_d);
  }
  c.H_body = kp.tail<3>().cwiseProduct(e_att) - kd.tail<3>().cwiseProduct(s.omega);
  return c;
}

}  // namespace pronk::control
