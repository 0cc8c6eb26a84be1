// The robot scene: one description of a ballistic running robot (body, legs,
// controller, setpoint, initial state, disturbances, simulation settings) that
// every model simulates. Built by io::load_scene; immutable once built.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/control/allocation.hpp"
#include "sim/math/rotation.hpp"
#include "sim/ode/solver.hpp"

namespace pronk::scene {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Which model simulates the scene. kMujoco: the full model's robot and controller with MuJoCo
/// as the engine (sim/mujoco/; optional at build time, mujoco_available()).
enum class ModelKind { kImpulse, kPulse, kPseudoRigid, kMujoco };
std::string_view to_string(ModelKind k);
/// Every model's name as scenes, studies and `--model` spell it, in ModelKind order (the one
/// list: a model added is added here and to ModelKind).
const std::vector<std::string>& model_names();
/// The model named `name`, or nothing for a name that is none of model_names().
std::optional<ModelKind> model_kind(std::string_view name);
/// The names of the models this build runs, as an error's "expected": "impulse", "pulse",
/// "pseudo_rigid" or "mujoco" (without MuJoCo: the first three, and how to get the fourth).
std::string model_names_expected();

/// The full model's robot and controller (legs, feet, hip placement, the `pseudo_rigid`
/// settings): pseudo_rigid and mujoco. The reduced models are the others.
inline bool is_full_model(ModelKind k) {
  return k == ModelKind::kPseudoRigid || k == ModelKind::kMujoco;
}

/// True when this build has MuJoCo (libmujoco-dev found by CMake): "model": "mujoco" runs.
bool mujoco_available();

/// Attitude integration: exact quaternion kinematics, or the seed's small-angle
/// formulation (1-2-3 Euler angles integrated as if they were body-rate integrals).
enum class AttitudeFormulation { kQuaternion, kSmallAngleEuler123 };

/// Rigid body mass properties.
struct Body {
  double mass = 1.5;  ///< [kg]
  /// Inertia tensor about the CoM in the body frame [kg m^2] (symmetric positive
  /// definite, satisfying the triangle inequalities of its principal moments).
  Mat3 inertia = Vec3(0.0074, 0.0106, 0.0164).asDiagonal();
};

/// Legs: none (body-only: one virtual leg at the CoM that can push any P and H)
/// or telescoping legs with rotary hips that push along the leg only (no body-y).
struct Legs {
  bool body_only = true;
  std::vector<Vec3> hips;      ///< hip positions relative to the CoM, body frame [m]
  std::vector<bool> disabled;  ///< per hip: failed leg, never used
  double length = 0.25;        ///< touchdown when the CoM falls through this height [m]
};

/// Gait: which legs push at a stride.
enum class Gait {
  kPronk,      ///< all working legs every stride
  kAlternate,  ///< trot/bound: alternates between gait_groups[0] and gait_groups[1]
};

/// The body controller: PD per axis + hop-height law + moving setpoint + banking.
struct Controller {
  /// Proportional gains for (x, y, z, roll, pitch, yaw) [N s/m, N s/m, -, N m s/rad ...].
  Vec6 kp = Vec6::Zero();
  /// Derivative gains for (x, y, z, roll, pitch, yaw) [kg, kg, kg, kg m^2 ...].
  Vec6 kd = Vec6::Zero();
  double hop_height = 0.2;  ///< desired apex height above touchdown height h [m]
  /// Vertical law. false: the seed's hop-height law, desired takeoff speed
  /// sqrt(2 g h) (exact for impulses). true (pulse model, duration mode): the
  /// takeoff speed v1 that reaches the apex l + h after a stance of duration T
  /// with constant force, given the touchdown speed v0:
  /// (v0 + v1) T / 2 + v1^2 / (2 g) = h.
  bool pulse_aware_hop = false;
  Vec3 setpoint_position = Vec3::Zero();  ///< x_d0 at t = 0 [m] (z unused)
  Vec3 setpoint_velocity = Vec3::Zero();  ///< v_d [m/s] (z unused)
  double setpoint_yaw = 0.0;              ///< desired heading [rad]
  /// Banking (legged only): desired roll = -clamp(kp e_y + kd e_vy, ±max_roll),
  /// world y errors expressed in the heading frame.
  /// Off in a scene built in code; the loader turns it on for legged robots unless the
  /// scene says otherwise, with gains scaled to the robot (sim/scene/robot_scaling.hpp).
  bool bank_enabled = false;
  double bank_kp = 0.0;         ///< [rad/m]
  double bank_kd = 0.0;         ///< [rad s/m]
  double bank_max_roll = 0.35;  ///< [rad]
  control::AllocationOptions allocation;
  Gait gait = Gait::kPronk;
  std::vector<std::vector<int>> gait_groups;  ///< leg index groups for kAlternate
  /// Hop-height setpoint changes (time [s], new hop height [m]), sorted by time
  /// (Ridgely 2001, fig. 2.13). Used by the pseudo-rigid model; the reduced models ignore it.
  std::vector<std::pair<double, double>> hop_height_changes;
};

/// Pulse model settings (Ridgely 2001, §2.6).
enum class PulseMode { kMaxForce, kDuration };
struct Pulse {
  PulseMode mode = PulseMode::kMaxForce;
  double max_force = 60.0;           ///< per-leg force limit in max_force mode [N]
  double duration = 0.05;            ///< stance duration T in duration mode [s]
  bool gravity_compensation = true;  ///< add m g T to the vertical impulse (Ridgely 2001, §2.6.1)
};

/// Settings only the pseudo-rigid model uses (Ridgely 2001, §2.7-2.8; docs/full_model.md). The
/// reduced models accept and ignore them. The ground is the plane z = 0, as
/// in the reduced models (touchdown when the CoM falls through legs.length).
/// The defaults are those of a running robot (spring legs, hip placement, level feet,
/// friction, the energy thrust and the trims, as pr_running and study 3 run); the loader
/// derives the leg stiffness, the stance attitude gains and the contact damping from the
/// robot (sim/scene/robot_scaling.hpp), so their numbers here stand only for scenes built
/// in code.
struct PseudoRigid {
  /// Hips: ghost points (forces transferred to the four body masses) or dummy
  /// masses tied to them (Ridgely 2001, §4.3).
  enum class Hips { kGhost, kDummy };
  /// Legs: `force` = leg forces act at the hips only, no leg or foot is modelled
  /// (Ridgely 2001, §2.7); `spring` = a foot mass on a line through the hip (prismatic
  /// leg) with a leg spring, damper and actuator in parallel (Ridgely 2001, §2.8).
  enum class Legs { kForce, kSpring };
  /// Body: one rigid body with the robot's mass and inertia (the default;
  /// sim/pseudorigid/rigid_body.hpp; ghost-point hips only), or four masses held by six
  /// internal springs (the body's flexibility resolved; the default with dummy-mass hips).
  /// A flat robot's four masses form a flat tetrahedron whose bending mode is soft (tens of
  /// hertz at 1e5 N/m) and takes up the thrust, so the body is rigid unless a scene asks for
  /// its flexibility (docs/full_model.md#the-body).
  enum class BodyKind { kFourMasses, kRigid };
  Hips hips = Hips::kGhost;
  BodyKind body = BodyKind::kRigid;
  double dummy_ratio = 0.02;  ///< dummy mass / body mass [-]
  Legs legs = Legs::kSpring;
  double internal_stiffness = 1e5;   ///< body springs, also the leg slides [N/m]
  bool internal_auto = false;        ///< choose it from strain_budget
  double internal_damping = 0.0;     ///< [N s/m]
  double contact_stiffness = 1e5;    ///< foot-ground springs [N/m]
  bool contact_auto = false;         ///< choose it from penetration_budget
  double contact_damping = 0.0;      ///< [N s/m]
  double strain_budget = 1e-4;       ///< allowed internal strain for "auto" [-]
  double penetration_budget = 1e-4;  ///< allowed penetration for "auto" [m]
  double foot_mass = 0.01;           ///< [kg]
  /// Feet (spring legs): point masses of foot_mass on the leg slides, or quasi-static
  /// (massless): an algebraic point at the leg's rest length in the air and, on the ground,
  /// held where force balance puts it, its ground position integrated by the regularised
  /// friction law's creep (sim/robot/robot_system_feet.cpp; rigid body only).
  enum class Feet { kMass, kQuasiStatic };
  Feet feet = Feet::kMass;
  double leg_stiffness = 100.0;  ///< leg spring [N/m]
  double leg_damping = 0.0;      ///< leg damper [N s/m]
  /// Leg actuator force limit [N]; 0 = unlimited. A saturated pulse delivers less
  /// than requested unless impulse_feedback keeps the actuator on.
  double actuator_max_force = 0.0;
  /// Actuation error: every leg actuator delivers this times the force it is commanded
  /// (the stance feedback's included), before its force limit. 1 = exact; a robust design
  /// draws it per trial ("perturb"), the controller does not know it [-].
  double actuator_gain = 1.0;
  /// Sensing error: the roll and pitch the controllers read are the body's plus this
  /// (about body x and y; the stride controller at touchdown and at the placement, the
  /// stance attitude feedback continuously; rates are read exactly). 0 = exact [rad].
  Eigen::Vector2d attitude_sensor_bias = Eigen::Vector2d::Zero();
  /// Leg controllers close the loop on delivered impulse (Ridgely 2001, §5.4): each actuator
  /// stays on until the impulse it delivered reaches its allocation.
  bool impulse_feedback = false;
  /// false: passive legs, the controller never acts (drop tests, Ridgely 2001, fig. 2.11).
  bool actuators = true;
  double friction = 1.0;        ///< Coulomb coefficient mu [-]; 0 = frictionless feet
  double slip_velocity = 1e-3;  ///< regularisation speed of the friction law [m/s]
  /// Hip actuators place each leg at the flight apex along the impulse the
  /// controller will ask it for at the predicted touchdown (running).
  bool hip_rotation = true;
  /// How the hips place the legs (with hip_rotation): true = the stance's horizontal motion
  /// solved as an inverted pendulum over the foot (sim/robot/leg_placement.hpp,
  /// pendulum_leg_direction; scene "hip_rotation": "pendulum", the default); false = the
  /// linear neutral-point rule (free_leg_direction; "hip_rotation": true or "neutral_point",
  /// what the scenes recorded before it ran).
  bool pendulum_placement = true;
  double max_leg_angle = 0.5;  ///< hip placement limit from body -z [rad]
  /// Stance attitude feedback (running): while feet are on the ground, the grounded
  /// legs' actuators add forces with zero net push that give the body a moment
  /// M = -kp e - kd w about its roll (x) and pitch (y) axes, evaluated
  /// continuously (e: tilt of the body z axis from the vertical, body frame [rad];
  /// w: body angular velocity [rad/s]). Gains [N m/rad], [N m s/rad]; 0 = off.
  double stance_kp[2] = {0.0, 0.0};
  double stance_kd[2] = {0.0, 0.0};
  double stance_max_moment = 0.0;  ///< smooth limit of each moment [N m]; 0 = none
  bool stance_feedback() const {
    return stance_kp[0] != 0.0 || stance_kp[1] != 0.0 || stance_kd[0] != 0.0 || stance_kd[1] != 0.0;
  }
  /// Level feet (running, with hip_rotation): at the flight apex each leg's spring
  /// rest length is set (leg-length actuator, within +-25 % of nominal) so that all
  /// feet reach the ground together at the predicted touchdown attitude; the energy
  /// change is booked as hip work.
  bool level_feet = true;
  /// Hop-height feedback (spring legs): after each flight apex the vertical takeoff
  /// speed asked of the legs changes by gain x (sqrt(2 g h) - sqrt(2 g h_apex)), h_apex
  /// the apex just measured above the leg length, so the losses in leg and foot
  /// dampers that the elastic-rebound law does not model are made up stride by
  /// stride (1 = dead-beat for a constant loss). 0 = off [-].
  double hop_trim_gain = 0.5;
  /// Anti-windup of that feedback: the extra takeoff speed asked stays within
  /// [-1, hop_trim_max] x sqrt(2 g h). Legs whose dampers take much of the stance
  /// energy need more than one sqrt(2 g h) [-].
  double hop_trim_max = 1.0;
  /// How spring legs thrust (actuators on from the bottom of the stance):
  /// kImpulse: each leg's planned impulse as a constant force over the pulse duration
  /// (the planned impulse assumes an elastic rebound; hop_trim_gain makes up the losses);
  /// kEnergy: the collective force that sends the body to the target apex by the legs'
  /// spring-damper model (sim/robot/thrust_law.hpp), held until the predicted lift-off, the
  /// legs' differential (attitude) impulses spread over the same time; hop_trim_gain then
  /// trims the target apex by the measured apex error (x gain per stride, within
  /// [-1, hop_trim_max] x h).
  enum class Thrust { kImpulse, kEnergy };
  /// Position feedback's integral action, per stride: at each touchdown the controller's
  /// measured horizontal position is offset by the running sum of gain x (x - x_d) over the
  /// touchdowns so far (within +-0.5 m), so a steady force bias the body controller's PD
  /// would balance with a standing error (the full model's leaning legs under a moving
  /// setpoint) is learnt away; 0 = off [-].
  double position_trim_gain = 0.3;
  /// Attitude feedback's integral action, per stride: at each touchdown the controller's
  /// measured roll and pitch are offset by the running sum of gain x (roll, pitch) over the
  /// touchdowns so far (within +-attitude_trim_max), so a steady moment bias (the full
  /// model's hip placement and stance feedback under a moving setpoint) that the body
  /// controller's PD would balance with a standing tilt is learnt away; 0 = off [-].
  double attitude_trim_gain = 1.0;
  /// Anti-windup of that trim: each of roll and pitch stays within +-attitude_trim_max. The
  /// stance feedback turns the trim into a moment stance_kp x trim, so a robot whose steady
  /// moment bias is large against its stance stiffness needs more [rad].
  double attitude_trim_max = 0.2;
  /// Leg placement's integral action, per stride (spring legs with hip_rotation): after each
  /// stance the horizontal impulse the placed legs missed (requested at the placement minus
  /// delivered from touchdown to apex) times this gain is added to the impulse the next
  /// placements lean the legs for (within the body's takeoff momentum m sqrt(2 g h)). The
  /// neutral-point placement delivers a horizontal impulse that changes by several N s per
  /// centimetre of foot position, so a millimetre of model error (leg compression, the
  /// thrust's timing, foot mass) is a steady push the PD and the position trim fight; this
  /// learns it away. 0 = off [-].
  double placement_trim_gain = 0.0;
  Thrust thrust = Thrust::kEnergy;
  /// Energy blow-up: a run whose energy balance drifts by more than this times the run's
  /// energy scale ends diverged. The mechanisms' setting (pseudorigid::SimulationOptions::
  /// energy_blowup_factor), with its default [-].
  double energy_blowup_factor = 10.0;
  /// Error norm of the adaptive solver: false = every state (resolves the stiff
  /// springs' vibration, energy balance exact to tolerance), true = body level
  /// (CoM, attitude, free masses; cheaper, vibration left unresolved).
  bool body_error_norm = false;
  /// The full model's solver when a method is named (solver_auto false; the settings a named
  /// method starts from: rodas4, rtol 1e-6, atol 1e-8). Under auto, its h_max, max_steps, ...
  ode::SolverOptions solver = default_solver();
  /// Method verlet ("solver": {"energy_tol"}): bound on Verlet's bounded energy term,
  /// relative to the run's energy scale (solver.verlet_energy_budget = energy_tol x scale,
  /// sub-stepping the impacts); 0 = off. [-]
  double energy_tol = 0.0;
  /// "solver": {"method": "auto"}, the default: the run chooses the method and its step or
  /// tolerances from its mechanism (sim/pseudorigid/method_choice.hpp); `solver` then holds
  /// the rest (h_max, max_steps, ...). Set it false to run `solver.method`.
  bool solver_auto = true;
  /// auto's target: the largest sampled energy-balance drift, relative to the run's energy
  /// scale ("solver": {"accuracy"}) [-].
  double accuracy = 1e-3;
  static ode::SolverOptions default_solver() {
    ode::SolverOptions s;
    s.method = ode::Method::kRodas4;
    s.rtol = 1e-6;
    s.atol = 1e-8;
    s.h_max = 0.01;
    s.event_tol = 1e-10;
    return s;
  }
};

/// Settings only "model": "mujoco" uses (sim/mujoco/robot_mjcf.hpp): MuJoCo's own integrator
/// and step. The contact's stiffness, damping and friction, the legs and the controller are the
/// `pseudo_rigid` settings.
struct Mujoco {
  enum class Integrator { kEuler, kRk4 };
  /// [s]: the largest step at which MuJoCo agrees with the full model on the robustness of study
  /// 3's design and the tripod's (docs/mujoco.md#agreement); 1 ms loses the nominal tripod.
  double timestep = 1.25e-4;
  Integrator integrator = Integrator::kEuler;
};

/// Initial state.
struct Initial {
  Vec3 position = Vec3(0, 0, 0.3);  ///< CoM [m]
  Vec3 velocity = Vec3::Zero();     ///< CoM velocity [m/s]
  math::Quat attitude = math::Quat::Identity();
  Vec3 angular_velocity = Vec3::Zero();  ///< body frame [rad/s]
};

/// An instantaneous disturbance: a velocity kick at a given time.
struct Disturbance {
  double time = 0.0;                    ///< [s]
  Vec3 linear_impulse = Vec3::Zero();   ///< world frame [N s]
  Vec3 angular_impulse = Vec3::Zero();  ///< body frame [N m s]
};

/// Run settings.
struct Simulation {
  double duration = 10.0;          ///< simulated time [s]
  long max_strides = 1000000;      ///< stop after this many touchdowns
  double sample_interval = 0.005;  ///< trajectory output interval [s]
  ode::SolverOptions solver;
  double fall_min_height = 0.0;  ///< CoM below this is a fall [m]; default 0.4 * leg length
  double fall_max_tilt = 1.0471975511965976;  ///< tilt of body z from vertical that is a fall [rad]
};

/// What the controller assumes about the robot when the robot differs from it: a robust-design
/// scenario perturbs the robot (the plant) and keeps here the nominal numbers the controller was
/// designed with. The controller's laws read these (the pulse model's gravity compensation, the
/// full model's elastic-rebound and energy-thrust laws, its stance-time estimate, its actuator
/// limit); the dynamics read the scene's own. The inertia is known to the controller only
/// through its gains, which were made absolute with the nominal numbers before any perturbation.
struct ControllerModel {
  Body body;                        ///< nominal mass and inertia
  double pulse_max_force = 60.0;    ///< pulse model, max_force mode: per-leg force limit [N]
  double leg_stiffness = 100.0;     ///< full model: leg spring [N/m]
  double leg_damping = 0.0;         ///< full model: leg damper [N s/m]
  double actuator_max_force = 0.0;  ///< full model: leg actuator limit [N]; 0 = unlimited
};

struct Scene {
  std::string name = "scene";
  ModelKind model = ModelKind::kImpulse;
  double gravity = 9.81;  ///< [m/s^2]
  AttitudeFormulation attitude = AttitudeFormulation::kQuaternion;
  Body body;
  Legs legs;
  Controller controller;
  Pulse pulse;
  PseudoRigid pseudo_rigid;
  Mujoco mujoco;
  Initial initial;
  std::vector<Disturbance> disturbances;  ///< sorted by time
  Simulation simulation;
  /// Unset (every scene as loaded): the controller knows the robot's numbers. Set by a
  /// robust-design scenario that perturbs the robot (optimize/scenario.hpp).
  std::optional<ControllerModel> controller_model;
};

/// The numbers the controller assumes: the scene's own, or its controller_model.
ControllerModel controller_model_of(const Scene& s);

/// The scene as its controller sees it: the scene with controller_model's numbers in place of
/// the robot's (the scene itself when controller_model is unset).
Scene controller_view(const Scene& s);

/// Seed gains (A.1): Kp = 1.0 (m, m, 0, Ixx, Iyy, Izz), Kd = 1.5 (m, m, m/1.5, Ixx, Iyy, Izz).
void seed_gains(const Body& body, Vec6* kp, Vec6* kd);

}  // namespace pronk::scene
