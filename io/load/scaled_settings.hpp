// Scene settings that scale with the robot, on the loader's side: what the controller and
// pseudo_rigid sections gave (absolute numbers, relative forms, or nothing), read by their
// readers, and the rules (sim/scene/robot_scaling.hpp) that turn the relative forms and the
// robot-scaled defaults into the absolute numbers of the Scene once the whole scene is read:
// a relative gain needs the body, a stride period needs the hop height and the pulse.
#pragma once

#include <optional>
#include <string>

#include "io/load/json_reader.hpp"
#include "sim/scene/robot_scaling.hpp"

namespace pronk::io {

/// The full model's stance attitude gains per unit inertia (Ixx, Iyy): kp [1/s^2], kd [1/s].
struct RelativeStanceGains {
  double kp[2] = {0.0, 0.0};
  double kd[2] = {0.0, 0.0};
};

/// What a scene gave for the settings that scale with the robot.
struct GivenSettings {
  bool kp = false, kd = false;                ///< "controller": absolute "kp", "kd"
  std::optional<scene::RelativeGains> gains;  ///< "controller": {"gains"}
  bool bank = false;                          ///< "controller": {"bank"}
  bool bank_kp = false, bank_kd = false;      ///< its "kp", "kd"
  bool leg_stiffness = false;                 ///< "pseudo_rigid": a number [N/m]
  double leg_stance_time = 0.0;               ///< {"leg_stiffness": {"stance_time"}} [s]
  bool stance_attitude = false;               ///< "pseudo_rigid": {"stance_attitude"}
  std::optional<RelativeStanceGains> stance;  ///< {"stance_attitude": {"gains"}}
  bool contact_damping = false;               ///< "pseudo_rigid": "contact_damping"
  bool foot_mass = false;                     ///< "pseudo_rigid": "foot_mass"
  bool leg_damping = false;                   ///< "pseudo_rigid": "leg_damping"
  bool position_trim_gain = false;            ///< "pseudo_rigid": "position_trim_gain"
};

/// Refuses an object (the controller, the stance attitude feedback) that gives both absolute
/// "kp"/"kd" and relative "gains".
void refuse_both_gain_forms(const JsonReader& r);

/// Reads "controller": {"gains": {...}}: either "kp" and "kd" (6 each, per unit mass and
/// inertia) or "natural_frequency" and "damping_ratio" (5 each: x, y, roll, pitch, yaw).
scene::RelativeGains parse_relative_gains(JsonReader g);

/// Reads "stance_attitude": {"gains": {"kp": [2], "kd": [2]}} (per unit inertia).
RelativeStanceGains parse_relative_stance_gains(JsonReader g);

/// Applies the relative forms and the robot-scaled defaults to the parsed scene *s.
/// Throws InputError (file, pointer, expected, found) when a stride response cannot be
/// sampled once per stride (a frequency above the stride's Nyquist limit).
void resolve_scaled_settings(const GivenSettings& given, const std::string& file, scene::Scene* s);

}  // namespace pronk::io
