// Settings that scale with the robot. A scene may write the body controller's gains, the
// full model's stance attitude feedback and its leg stiffness relative to the robot (per
// unit mass and inertia, as a stride response, as a stance time), and the defaults it
// leaves out are derived from the robot the same way. These rules turn them into the
// absolute numbers a Scene holds. The loader applies them once, to the nominal scene, so a
// run whose robot is perturbed afterwards (mass, inertia) keeps the controller tuned for the
// nominal robot, as a real controller would.
#pragma once

#include "sim/scene/scene.hpp"
#include "sim/scene/stride_response.hpp"

namespace pronk::scene {

/// The scale of relative gains: (m, m, m, Ixx, Iyy, Izz), the inertia about each body axis
/// (the tensor's diagonal) [kg, kg m^2].
Vec6 gain_scale(const Body& body);

/// The stance the robot's legs are designed for [s]: the pulse duration (duration mode), or
/// in max_force mode the time the working legs of one stride (n of them, force F each) take
/// to deliver the orbit's vertical impulse: Ts = 2 m v / (n F - m g) with gravity
/// compensation (2 m v / (n F) without), v = sqrt(2 g h).
double design_stance_time(const Scene& s);

/// The stride the body controller is designed for, at the gait's orbit: flight from the hop
/// height (hop_flight_time), stance from design_stance_time (none in the impulse model).
StrideTiming design_stride(const Scene& s);

/// Controller gains written relative to the robot ("controller": {"gains": ...}).
struct RelativeGains {
  enum class Form { kPerUnit, kResponse };
  Form form = Form::kPerUnit;
  Vec6 kp = Vec6::Zero();  ///< per unit mass / inertia [1/s] (kPerUnit)
  Vec6 kd = Vec6::Zero();  ///< per unit mass / inertia [-] (kPerUnit)
  /// Stride response of x, y, roll, pitch, yaw (kResponse): natural frequency [rad/s] and
  /// damping ratio [-]; the vertical channel keeps the hop-height law (kd_z = m, kp_z = 0).
  Eigen::Matrix<double, 5, 1> natural_frequency = Eigen::Matrix<double, 5, 1>::Zero();
  Eigen::Matrix<double, 5, 1> damping_ratio = Eigen::Matrix<double, 5, 1>::Zero();
};

/// Index into the 6 axes (x, y, z, roll, pitch, yaw) of the response form's 5 channels.
constexpr int kResponseAxis[5] = {0, 1, 3, 4, 5};

/// The largest natural frequency a channel of damping ratio zeta can have on stride period T:
/// the sampled pair's angle omega T sqrt(1 - zeta^2) stays below pi (no aliasing); no limit
/// (infinity) from zeta 1 on [rad/s].
double max_natural_frequency(double zeta, double period);

/// Absolute gains (N s/m, kg, N m s/rad, kg m^2 per axis) from relative ones on scene s.
void absolute_gains(const RelativeGains& g, const Scene& s, Vec6* kp, Vec6* kd);

/// The poles the legged robot's default lateral loop (roll PD and banking) is placed at,
/// per stride: 0.4, 0.5, 0.6, 0.7 (an error falls to 1 % within about 20 strides, and the
/// loop stays stable with its push or roll effectiveness off by +-40 %).
constexpr std::array<double, 4> kLateralPoles = {0.4, 0.5, 0.6, 0.7};

/// The poles the full model's fore-aft position loop (x PD with the position trim) starts
/// from in a derived design, per stride: 0.6, 0.6, 0.6 (an error falls to 1 % within about
/// 15 strides). Measured on the tripod's design: its own tuned loop (poles 0.61 and
/// 0.80 +- 0.32i) stabilized 5 of 32 held-out trials, this one 22, poles at 0.5 21 with a fall.
constexpr std::array<double, 3> kPositionPoles = {0.6, 0.6, 0.6};

/// The full model's fore-aft position loop placed at kPositionPoles on the scene's design
/// stride (relative gains kp, kd per unit mass and the position trim gain).
PositionLoop default_position_loop(const Scene& s);

/// The default lateral loop of a legged scene: kLateralPoles placed on its design stride.
LateralLoop default_lateral_loop(const Scene& s);

/// The leg spring stiffness whose stance half-period on n legs is Ts:
/// k = m (pi / Ts)^2 / n [N/m] (n: every hip; the rule the full model's expected stance
/// inverts).
double leg_stiffness_for_stance(const Scene& s, double stance_time);

/// Defaults of the full model's stance attitude feedback, per unit inertia (Ixx, Iyy) of the
/// body: kp [1/s^2], kd [1/s]. Study 3's gains on pr_running's body (kp 0 and 15 N m/rad,
/// kd 6 and 6 N m s/rad over Ixx 0.0074 and Iyy 0.0106 kg m^2), rounded.
constexpr double kStanceKpPerInertia[2] = {0.0, 1400.0};
constexpr double kStanceKdPerInertia[2] = {800.0, 570.0};

/// The stance kp per unit inertia a scene gets by default (roll, pitch) [1/s^2]: study 3's,
/// except that a robot with a sideways setpoint velocity holds its roll as it holds its
/// pitch, in the share of the speed that is sideways: kp_roll = kp_pitch |v_y| / |v|. The
/// thrust at the bottom of the stance makes a steady moment about the axis across the
/// travel, which the attitude trim can only hold against a stance stiffness (the sidestepping
/// quadruped, 0.15 of 0.34 m/s sideways, held -5 deg of roll with its trim at its limit).
Eigen::Vector2d default_stance_kp_per_inertia(const Scene& s);

/// The duty a legged scene without a "pulse" runs at: pulses of the stance time
/// Ts = d Tf / (1 - d) on the hop's flight Tf, d = 0.2. In the full model the spring legs then
/// follow that stance; each family robot started level on these defaults completes its
/// 10 s, while the 60 N max-force pulses (6-45 ms stances) make the 0.5 kg quadruped fall in
/// its first stance.
constexpr double kDefaultDuty = 0.2;

/// The stance time of duty d on a flight Tf: d = Ts / (Ts + Tf), Ts = d Tf / (1 - d) [s].
double stance_for_duty(double duty, double flight);

/// The pulse duration of kDefaultDuty on the scene's hop (impulse flight) [s].
double default_pulse_duration(const Scene& s);

/// The leg damping a full-model scene gets when it gives none: a damping ratio of 0.2 on
/// each leg's share of the body on its stance spring, 0.2 * 2 sqrt(k m / n) [N s/m].
/// Undamped legs make the tripod fall within 3 s.
constexpr double kDefaultLegDampingRatio = 0.2;
double default_leg_damping(const Scene& s);

/// Default limit of each stance moment: the body's weight over its farthest hip,
/// m g max_i |(r_x, r_y)_i| [N m] (pr_running: 2.7 N m; its scene sets 3).
double default_stance_max_moment(const Scene& s);

/// Default foot mass: pr_running's ratio, 1 g per foot for its 1.5 kg body, m / 1500 [kg]
/// (10 g feet make pr_running fall within 5 s on the other defaults; 1 g feet run 10 s).
double default_foot_mass(const Body& body);

/// Default foot contact damping: critically damped feet on their contact springs,
/// 2 sqrt(k_contact m_foot) [N s/m] (pr_running: 20 N s/m, 1 g feet on 1e5 N/m).
double default_contact_damping(const PseudoRigid& p);

}  // namespace pronk::scene
