// The top layer of the control hierarchy (Ridgely 2001, §2.3-2.5.2): at touchdown the
// body controller turns the measured body state into the net linear impulse P
// (world frame) and angular impulse H (body frame) the legs must deliver.
#pragma once

#include "sim/control/body_state.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::control {

/// What the body controller asks for at one touchdown.
struct BodyCommand {
  Eigen::Vector3d P_world = Eigen::Vector3d::Zero();  ///< net linear impulse, world [N s]
  Eigen::Vector3d H_body = Eigen::Vector3d::Zero();   ///< net angular impulse, body [N m s]
  Eigen::Vector3d desired_euler123 = Eigen::Vector3d::Zero();  ///< attitude setpoint [rad]
};

/// Replaceable body-controller layer (a pulse-aware controller is another implementation).
class BodyController {
 public:
  virtual ~BodyController() = default;
  /// Command at a touchdown at time t [s] with state s. Pure: no hidden state.
  virtual BodyCommand command(double t, const BodyState& s) const = 0;
};

/// PD per axis with the hop-height law, a moving setpoint and (optionally) banking.
/// Linear: P_i = Kp_i (x_d,i - x_i) + Kd_i (v_d,i - v_i) with x_d = x_d0 + v_d t;
/// vertical: P_z = Kd_z (sqrt(2 g h) - v_z) (Kp_z multiplies the height error
/// relative to the leg length, zero at touchdown). Angular: H = Kp ∘ e + Kd ∘ (0 - w)
/// with e the attitude error in the body frame: the rotation vector of q^-1 q_d
/// (exact), or theta_d - theta (small-angle formulation, Ridgely 2001, App. A.1).
class PdBodyController final : public BodyController {
 public:
  /// stance_duration [s]: the pulse duration the pulse-aware hop law plans for (0: impulses).
  PdBodyController(const scene::Controller& config, double gravity, double leg_length, bool legged,
                   bool small_angle, double stance_duration = 0.0);
  BodyCommand command(double t, const BodyState& s) const override;

 private:
  const scene::Controller& config_;
  double takeoff_speed_;    ///< sqrt(2 g h) [m/s]
  double gravity_;          ///< [m/s^2]
  double stance_duration_;  ///< T of the pulse-aware hop law [s]; 0 = seed law
  double leg_length_;       ///< [m]
  bool bank_;
  bool small_angle_;
};

}  // namespace pronk::control
