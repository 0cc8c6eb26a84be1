// The robot of a scene as an MJCF model for MuJoCo ("model": "mujoco"): the body a free rigid
// body with the scene's mass and inertia; per leg, at its hip, a roll hinge, a pitch hinge and a
// slide (leg_joints.hpp) carrying the foot mass as a small sphere, the leg spring and damper as
// the slide's stiffness and damping (rest length as its spring reference), the leg actuator a
// motor on the slide, and the hip placement two joint equalities (roll and pitch held at their
// targets; the run frees the pitch in stance, as the pseudo-rigid robot's slot does). The ground
// is a plane whose contact with the feet takes the scene's stiffness, damping and friction.
//
// MuJoCo's contact is a soft constraint on accelerations: its reference acceleration
// a_ref = -B v - K r is the scene's spring and damper per unit foot mass, K = k / m_foot and
// B = c / m_foot, i.e. the foot's contact frequency omega = sqrt(k / m_foot). A mode faster than
// MuJoCo's step resolves is limited to omega <= 1 / (2 timestep), MuJoCo's own rule (its time
// constant at least twice the step), keeping the damping ratio; the model's comment says when.
// The same rule sets the joint equalities' time constant (2 timesteps, critically damped).
#pragma once

#include <string>
#include <vector>

#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::mujoco {

/// Radius of the foot spheres [m]; the ground plane lies that far below z = 0, so that the
/// sphere's centre (the pseudo-rigid robot's point foot) touches down at z = 0.
constexpr double kFootRadius = 0.005;

/// MuJoCo's name of the scene's integrator ("Euler", "RK4"), as MJCF and the outputs spell it.
const char* integrator_name(scene::Mujoco::Integrator integrator);

/// The contact's numbers as MJCF takes them.
struct ContactParameters {
  double stiffness = 0.0;  ///< K, reference stiffness per unit mass [1/s^2]
  double damping = 0.0;    ///< B [1/s]
  double omega = 0.0;      ///< the scene's foot contact frequency sqrt(k / m_foot) [rad/s]
  bool limited = false;    ///< omega was above 1 / (2 timestep)
};

/// The contact of scene s's feet (foot mass m_foot [kg]) at MuJoCo step `timestep` [s].
ContactParameters contact_parameters(const scene::Scene& s, double foot_mass);

/// Names of the model's elements, leg i.
std::string leg_body_name(size_t i);
std::string roll_joint_name(size_t i);
std::string pitch_joint_name(size_t i);
std::string slide_joint_name(size_t i);
std::string roll_hold_name(size_t i);
std::string pitch_hold_name(size_t i);
std::string thrust_name(size_t i);

/// The MJCF text of scene s's robot (model: build_robot of s with the rigid body). key_qpos and
/// key_qvel, when not empty, become the keyframe "initial" (the run's initial state), so that
/// MuJoCo's viewer opens the robot where the run starts.
std::string robot_mjcf(const scene::Scene& s, const robot::RobotModel& model,
                       const std::vector<double>& key_qpos = {},
                       const std::vector<double>& key_qvel = {});

}  // namespace pronk::mujoco
