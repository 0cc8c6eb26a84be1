#include "sim/robot/robot_simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <utility>

#include "sim/control/stance_planner.hpp"
#include "sim/math/rotation.hpp"
#include "sim/ode/verlet.hpp"
#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/pseudorigid/stability.hpp"
#include "sim/reduced/run_limits.hpp"
#include "sim/reduced/run_record.hpp"
#include "sim/robot/robot_system.hpp"
#include "sim/robot/thrust_law.hpp"
#include "sim/run/hybrid_run.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

struct Com {
  Vector3d x, v;  ///< [m], [m/s]
};

/// CoM position and velocity of the body: its four main masses and its dummy masses.
Com body_com(const RobotModel& m, const ode::Vec& y) {
  Com c{Vector3d::Zero(), Vector3d::Zero()};
  double total = 0.0;
  for (size_t j = 0; j < m.mechanism.masses.size(); ++j) {
    const auto& ms = m.mechanism.masses[j];
    if (ms.body != m.body && ms.dummy_of != m.body) continue;
    c.x += ms.mass * y.segment<3>(6 * j);
    c.v += y.segment<3>(6 * j + 3);
    total += ms.mass;
  }
  c.x /= total;
  c.v /= total;
  return c;
}

/// The spring-leg leg layer (seed 2.8.1): the springs return the touchdown
/// momentum, so the actuators are asked for the body controller's request minus
/// the elastic rebound -2 m v_z. Wraps the unchanged body controller.
class SpringReboundController final : public control::BodyController {
 public:
  /// push: the legs' common push direction, body frame (prismatic legs push only
  /// along it, so the linear request is projected on it before allocation).
  /// hips: mean hip position, body frame [m]; gravity [m/s^2]; stance: expected
  /// stance duration [s] (0: the springs' moment is not compensated).
  /// trim: extra vertical takeoff speed asked of the legs (hop-height feedback) [m/s].
  SpringReboundController(const control::BodyController& inner, double mass, const Vector3d* push,
                          const Vector3d& hips, double gravity, const double* stance,
                          const double* trim)
      : inner_(inner),
        mass_(mass),
        push_(push),
        hips_(hips),
        gravity_(gravity),
        stance_(stance),
        trim_(trim) {}
  control::BodyCommand command(double t, const control::BodyState& s) const override {
    control::BodyCommand c = inner_.command(t, s);
    const double rebound = -2.0 * mass_ * std::min(0.0, s.velocity.z());  // [N s]
    c.P_world.z() += mass_ * *trim_ - rebound;
    const Vector3d d = s.rotation * *push_;
    c.P_world = c.P_world.dot(d) * d;
    // The springs' impulse (rebound plus the weight over the stance) acts along the
    // legs at the hips, off the CoM when the legs lean: its moment is the actuators'
    // to cancel, or it pitches the body (legs at the hips below the CoM).
    if (d.z() > 0.1) {
      const Vector3d P_springs = (rebound + mass_ * gravity_ * *stance_) / d.z() * d;
      c.H_body -= hips_.cross(s.rotation.transpose() * P_springs);
    }
    return c;
  }

 private:
  const control::BodyController& inner_;
  double mass_;
  const Vector3d* push_;
  Vector3d hips_;
  double gravity_;
  const double* stance_;
  const double* trim_;
};

class ComHeightEvent final : public ode::EventFunction {
 public:
  ComHeightEvent(const RobotModel& m, double level) : m_(m), level_(level) {}
  double value(double, const ode::Vec& y) const override { return body_com(m_, y).x.z() - level_; }

 private:
  const RobotModel& m_;
  double level_;
};

class ApexEvent final : public ode::EventFunction {
 public:
  explicit ApexEvent(const RobotModel& m) : m_(m) {}
  double value(double, const ode::Vec& y) const override { return body_com(m_, y).v.z(); }

 private:
  const RobotModel& m_;
};

/// Bottom of a spring stance: the CoM's vertical velocity rises through zero.
class BottomEvent final : public ode::EventFunction {
 public:
  explicit BottomEvent(const RobotModel& m) : m_(m) {}
  double value(double, const ode::Vec& y) const override { return body_com(m_, y).v.z(); }
  int direction() const override { return 1; }

 private:
  const RobotModel& m_;
};

/// A foot crossing the ground plane z = 0 falling while its hip is locked (the foot
/// lands: the hip is freed), or rising through kFootLift above it while the hip is
/// free (lift-off: locked again). The hysteresis keeps a foot grazing the ground
/// (z ~ 0, v_z ~ 0) from landing and lifting off at the same instant forever.
constexpr double kFootLift = 2e-4;  ///< [m]
class FootEvent final : public ode::EventFunction {
 public:
  FootEvent(const RobotSystem& sys, size_t leg, int foot) : sys_(sys), leg_(leg), foot_(foot) {}
  double value(double, const ode::Vec& y) const override {
    return y[6 * foot_ + 2] - (sys_.free(leg_) ? kFootLift : 0.0);
  }
  int direction() const override { return sys_.free(leg_) ? 1 : -1; }

 private:
  const RobotSystem& sys_;
  size_t leg_;
  int foot_;
};

class TiltEvent final : public ode::EventFunction {
 public:
  TiltEvent(const RobotModel& m, const pr::MechanismSystem& sys, double max_tilt)
      : m_(m), sys_(sys), cos_max_(std::cos(max_tilt)) {}
  double value(double, const ode::Vec& y) const override {
    return sys_.frames(y)[m_.body].rotation(2, 2) - cos_max_;
  }

 private:
  const RobotModel& m_;
  const pr::MechanismSystem& sys_;
  double cos_max_;
};

/// Per-run bookkeeping shared by the step observer and the loop.
struct Run {
  Run(const scene::Scene& s, const RobotModel& m, const RobotSystem& y,
      const pr::MechanismSystem& ms, RobotRunResult& o)
      : scene(s), model(m), sys(y), msys(ms), out(o) {}
  const scene::Scene& scene;
  const RobotModel& model;
  const RobotSystem& sys;
  const pr::MechanismSystem& msys;
  RobotRunResult& out;
  bool record = true;
  double dissipated = 0.0, work = 0.0;
  double positive_work = 0.0;  ///< leg actuators' work, positive steps only [J]
  double balance0 = 0.0;       ///< energy balance at the start [J]
  /// The worst sampled departure of the balance [J] and where it first exceeded `blowup`.
  double sampled_drift = 0.0, blowup = 0.0, blowup_time = -1.0, blowup_drift = 0.0;
  bool stance = false;
  std::vector<bool> in_contact;
  std::vector<Eigen::Vector2d> contact_start;
  double stride_slip = 0.0;
  double contact_begin = 0.0;  ///< free stance hips: first foot landing of this stance [s]

  control::BodyState body_state(const ode::Vec& y) const {
    const pr::BodyFrame& f = msys.frames(y)[model.body];
    const Com c = body_com(model, y);
    control::BodyState s;
    s.position = c.x;
    s.velocity = c.v;
    s.rotation = f.rotation;
    s.attitude = Eigen::Quaterniond(f.rotation).normalized();
    s.omega = f.rotation.transpose() * msys.body_omega(model.body, y);
    s.euler123 = math::matrix_to_euler(f.rotation, math::EulerSet::k123);
    return s;
  }

  /// The energy balance at a sample time t with the flows up to t: its departure from the
  /// start enters the drift monitor (and the blow-up check); with `record` the sample is kept.
  void sample(double t, const ode::Vec& y, double dissipated_t, double work_t) {
    const pr::Energies e = msys.energies(y);
    const double drift =
        std::abs(e.total() + dissipated_t - work_t - out.monitors.hip_work - balance0);
    sampled_drift = std::max(sampled_drift, std::isfinite(drift) ? drift : 1e300);
    if (blowup_time < 0.0 && !(drift <= blowup)) {
      blowup_time = t;
      blowup_drift = drift;
    }
    if (!record) return;
    const control::BodyState s = body_state(y);
    reduced::Sample smp;
    smp.t = t;
    smp.position = s.position;
    smp.velocity = s.velocity;
    smp.euler123 = s.euler123;
    smp.omega = s.omega;
    smp.setpoint = scene.controller.setpoint_position + scene.controller.setpoint_velocity * t;
    smp.stance = stance;
    RobotSample rs;
    rs.t = t;
    rs.energies = e;
    rs.dissipated = dissipated_t;
    rs.actuator_work = work_t + out.monitors.hip_work;
    rs.actuator_force = sys.actuator_forces(y);
    for (size_t i = 0; i < model.hip.size(); ++i) {
      // Σ actuator forces on the body (world), as the reduced models' leg force.
      smp.leg_force_world += rs.actuator_force[i] * sys.push_world(i, y);
    }
    if (model.spring_legs) {
      rs.normal_force = sys.normal_forces(y);
      for (int f : model.foot) rs.foot_z.push_back(y[6 * f + 2]);
    }
    out.run.trajectory.push_back(smp);
    out.samples.push_back(std::move(rs));
  }

  /// Monitors at the end of an accepted step.
  void monitor(const ode::Vec& y) {
    const pr::StateMonitors m = msys.monitors(y);
    out.monitors.max_strain = std::max(out.monitors.max_strain, m.max_strain);
    out.monitors.max_penetration = std::max(out.monitors.max_penetration, m.max_penetration);
    if (!model.spring_legs) return;
    for (size_t i = 0; i < model.foot.size(); ++i) {
      const int f = model.foot[i];
      const Eigen::Vector2d xy = y.segment<2>(6 * f);
      if (y[6 * f + 2] < 0.0) {
        if (!in_contact[i]) contact_start[i] = xy;
        in_contact[i] = true;
        const double slip = (xy - contact_start[i]).norm();
        stride_slip = std::max(stride_slip, slip);
        out.monitors.max_slip = std::max(out.monitors.max_slip, slip);
        const pr::MechanismSystem::Contact c =
            msys.contact(model.ground, pr::NodeRef{pr::NodeRef::Kind::kMass, f}, y);
        if (c.normal > 0.0) {
          out.monitors.max_friction_ratio =
              std::max(out.monitors.max_friction_ratio, c.friction.norm() / c.normal);
        }
      } else {
        in_contact[i] = false;
      }
    }
  }
};

// Energy put in (or taken out) by placing the legs [J].
void book_hip_work(RobotMonitors& m, double dE) {
  m.hip_work += dE;
  m.positive_hip_work += std::max(0.0, dE);
}

/// Energy flows, monitors and samples along the accepted steps. Method verlet books both
/// flows as its steps do: the dissipation is the stepper's own (MechanicalSystem::dissipate), the
/// actuator work 1/2 (F_a + F_b) . (x_b - x_a) over the masses with the actuator forces F at
/// the step's ends (then E - T + D - W is exact for quadratic potentials, T Verlet's bounded
/// term; docs/pseudorigid.md), both linear in time within a step. Other methods integrate
/// the dissipated and actuator power by Gauss-Legendre on the dense output. A sample inside
/// a step pairs its state with the flows up to the sample time.
class Observer final : public ode::StepObserver {
 public:
  Observer(Run& run, double interval, int n, bool verlet)
      : run_(run),
        interval_(interval),
        verlet_(verlet),
        yq_(n),
        ya_(n),
        fa_(run.sys.actuator_force_size()),
        fb_(run.sys.actuator_force_size()) {}
  void on_step(const ode::Stepper& st, double t_stop) override {
    const double ta = st.t_prev(), tb = t_stop;
    const double d_a = run_.dissipated, w_a = run_.work;
    double step_d = 0.0, step_w = 0.0;  // the whole step's flows (verlet) [J]
    if (verlet_) {
      const double booked = ode::booked_dissipation(st);
      step_d = booked - booked_;
      booked_ = booked;
      step_w = verlet_work(st);
    }
    flows(st, ta, tb, step_d, step_w, &run_.dissipated, &run_.work);
    run_.positive_work += std::max(0.0, run_.work - w_a);
    st.dense(tb, yq_);
    run_.monitor(yq_);
    while (next_ <= tb + 1e-12 * std::max(1.0, tb)) {
      const double ts = std::min(next_, tb);
      double d = d_a, w = w_a;
      flows(st, ta, ts, step_d, step_w, &d, &w);
      st.dense(ts, yq_);
      run_.sample(next_, yq_, d, w);
      next_ = interval_ * static_cast<double>(++count_);
    }
  }
  void start(const ode::Stepper& st, const ode::Vec& y) {
    booked_ = ode::booked_dissipation(st);
    run_.sample(0.0, y, run_.dissipated, run_.work);
    next_ = interval_ * static_cast<double>(++count_);
  }
  /// The stepper restarts (a new state or new actuator forces): the next step's start
  /// forces are evaluated afresh.
  void restart() { have_fa_ = false; }

 private:
  /// Adds the flows over [ta, te] of the current step (which ends at st.t()) to *d and *w;
  /// verlet: the fraction of the step's flows step_d, step_w [J].
  void flows(const ode::Stepper& st, double ta, double te, double step_d, double step_w, double* d,
             double* w) {
    if (verlet_) {
      const double frac = st.t() > ta ? (te - ta) / (st.t() - ta) : 1.0;
      *d += frac * step_d;
      *w += frac * step_w;
      return;
    }
    static const double s[3] = {0.5 - std::sqrt(15.0) / 10.0, 0.5, 0.5 + std::sqrt(15.0) / 10.0};
    static const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    for (int q = 0; q < 3; ++q) {
      st.dense(ta + s[q] * (te - ta), yq_);
      const double wq = gw[q] * (te - ta);
      const pr::PowerFlows p = run_.msys.power(yq_);
      *d += wq * p.dissipated;
      *w += wq * (p.actuator + run_.sys.actuator_power(yq_));
    }
  }

  /// Verlet's actuator work over its last step [J] (see the class comment); the forces at
  /// the step's end are kept for the next step's start.
  double verlet_work(const ode::Stepper& st) {
    if (!have_fa_) {
      st.dense(st.t_prev(), ya_);  // the step's start (the dense output's end point)
      on_a_ = run_.sys.actuator_mass_forces(ya_, fa_);
    }
    const ode::Vec& yb = st.y();
    const bool on_b = run_.sys.actuator_mass_forces(yb, fb_);
    double w = 0.0;
    const int nm = static_cast<int>(run_.model.mechanism.masses.size());
    for (int j = 0; j < nm; ++j) {
      Vector3d f = Vector3d::Zero();
      if (on_a_) f += fa_.segment<3>(3 * j);
      if (on_b) f += fb_.segment<3>(3 * j);
      w += 0.5 * f.dot(yb.segment<3>(6 * j) - ya_.segment<3>(6 * j));
    }
    const int r = run_.sys.rotation_state();
    if (r >= 0) {  // rigid body: the torque over the step's rotation (world rotation vector)
      Vector3d tau = Vector3d::Zero();
      if (on_a_) tau += fa_.segment<3>(3 * nm);
      if (on_b) tau += fb_.segment<3>(3 * nm);
      const Eigen::AngleAxisd turn(pr::rigid_quaternion(yb, r) *
                                   pr::rigid_quaternion(ya_, r).conjugate());
      w += 0.5 * tau.dot(turn.angle() * turn.axis());
    }
    ya_ = yb;
    fa_.swap(fb_);
    on_a_ = on_b;
    have_fa_ = true;
    return w;
  }

  Run& run_;
  double interval_;
  bool verlet_;
  ode::Vec yq_;
  ode::Vec ya_, fa_, fb_;  ///< verlet: the step's start state and the actuator forces at its ends
  bool on_a_ = false;      ///< fa_ holds forces (actuators act at the step's start)
  bool have_fa_ = false;   ///< ya_ and fa_ are the current step's start
  double next_ = 0.0;
  long count_ = 0;
  double booked_ = 0.0;  ///< the stepper's booked dissipation at the end of the last step [J]
};

/// The run's solver options: the scene's, with verlet's energy budget in joules
/// (energy_tol x the energy scale [J]).
ode::SolverOptions solver_options(const scene::PseudoRigid& prs, double energy_scale) {
  ode::SolverOptions solver = prs.solver;
  if (solver.method == ode::Method::kVerlet) {
    solver.verlet_energy_budget = prs.energy_tol * energy_scale;
  }
  return solver;
}

/// " (METHOD step H s[; verlet's stability bound])": the numbers of a divergence.
/// verlet_limit: 2 / (a bound on the highest spring frequency) [s], 0 for other methods.
std::string divergence_note(ode::Method method, double h, double verlet_limit) {
  std::string note = " (" + std::string(ode::to_string(method)) + " step " + run::fmt(h) + " s";
  if (verlet_limit > 0.0) {
    note += "; verlet is stable below h = 2/omega_max >= " + run::fmt(verlet_limit) +
            " s, omega_max the springs' highest frequency (bound)";
  }
  return note + ")";
}

/// Leg placement for the predicted touchdown: every leg parallel to the net linear
/// impulse the legs must deliver (body frame, no body-y part), within max_angle of
/// -z, so the spring rebound pushes where the impulse must go without adding a
/// moment of its own; the moments are left to the actuators. Unit directions hip -> foot.
std::vector<Vector3d> leg_directions(const control::StancePlan& plan, size_t legs,
                                     double max_angle) {
  std::vector<Vector3d> u(legs, -Vector3d::UnitZ());
  const Vector3d p = plan.P_body;
  if (!(p.z() > 1e-12)) return u;  // no upward push: legs straight down
  const double angle = std::clamp(std::atan2(p.x(), p.z()), -max_angle, max_angle);
  for (auto& ui : u) ui = Vector3d(-std::sin(angle), 0.0, -std::cos(angle));
  return u;
}

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
/// velocity v_takeoff in y instead (no neutral point).
Vector3d free_leg_direction(const Vector3d& P, const Vector3d& v, double stance, double leg,
                            double max_angle, bool held_roll, const Vector3d& v_takeoff) {
  Eigen::Vector2d r = 0.5 * stance * v.head<2>();
  if (P.z() > 1e-12) r -= leg * P.head<2>() / P.norm();
  if (held_roll && v_takeoff.z() > 1e-12) {
    r.y() = -leg * v_takeoff.y() / std::hypot(v_takeoff.y(), v_takeoff.z());
  }
  const double r_max = leg * std::sin(max_angle);
  if (r.norm() > r_max) r *= r_max / r.norm();
  return Vector3d(r.x(), r.y(), -std::sqrt(std::max(0.0, leg * leg - r.squaredNorm()))) / leg;
}

/// What a robot run changes as it goes, beside the const RobotModel (MuJoCo's mjData beside
/// its mjModel): the mechanism's run-time inputs, whose leg rest lengths and slide surfaces
/// the hip placement and the foot switches set (RobotSystem reads them there), the leg
/// actuators' commands, and the controller's adapted terms.
struct RunData {
  RunData(const RobotModel& model, const scene::Scene& scene)
      : inputs(model.mechanism),
        push(model.hip.size(), Vector3d::UnitZ()),
        leg_force(model.hip.size(), 0.0),
        off_time(model.hip.size(), 0.0),
        stride_force(model.hip.size(), 0.0),
        armed_force(model.hip.size(), 0.0),
        armed_duration(model.hip.size(), 0.0) {
    for (size_t i = 0; i < model.hip.size(); ++i) push[i] = -model.direction[i];
    // Expected stance duration of spring legs [s]: half a period of the body on its leg
    // springs until a stance is measured (free stance hips measure every stance).
    spring_stance =
        model.spring_legs
            ? M_PI * std::sqrt(scene.body.mass / (scene.pseudo_rigid.leg_stiffness *
                                                  static_cast<double>(model.hip.size())))
            : 0.0;
  }
  pr::MechanismInputs inputs;        ///< hip placement and the feet turn the slides
  std::vector<Vector3d> push;        ///< body-frame push direction of each actuator
  std::vector<double> leg_force;     ///< actuator force of each leg now [N]
  std::vector<double> off_time;      ///< when each actuator switches off [s]
  std::vector<double> stride_force;  ///< the stance's actuator forces, for the stride record [N]
  /// Spring legs: the actuators fire in the thrust phase, from the bottom of the stance (CoM
  /// velocity rising through zero) on, so a downward force lowers the takeoff speed and an
  /// upward one raises it (seed fig. 2.13).
  bool armed = false;
  std::vector<double> armed_force, armed_duration;
  Vector3d common_push = Vector3d::UnitZ();  ///< legs' push direction, body frame
  double spring_stance = 0.0;                ///< expected stance duration of spring legs [s]
  double hop_trim = 0.0;   ///< hop-height feedback: extra takeoff speed asked [m/s]
  double apex_trim = 0.0;  ///< hop-height feedback of the energy thrust: extra apex asked [m]
  Vector3d position_trim = Vector3d::Zero();  ///< integral action: position offset seen [m]
  Eigen::Vector2d attitude_trim = Eigen::Vector2d::Zero();  ///< integral action: roll, pitch [rad]
};

/// The same three control layers as the reduced models, planned as constant-force pulses
/// (the pulse settings), one set per hop-height setpoint (controller.hop_height_changes);
/// the spring legs' layer removes the rebound.
class ControlLayers {
 public:
  ControlLayers(const scene::Scene& scene, const RobotModel& model, const RunData& data)
      : spring_legs_(model.spring_legs) {
    scene::Scene plan_scene = scene;
    plan_scene.model = scene::ModelKind::kPulse;
    if (model.spring_legs) plan_scene.pulse.gravity_compensation = false;
    Vector3d mean_hip = Vector3d::Zero();  // body frame [m]
    for (const Vector3d& h : model.hip) mean_hip += h / static_cast<double>(model.hip.size());
    auto add_layer = [&](double from, double hop_height) {
      Layer L;
      L.scene = std::make_unique<scene::Scene>(plan_scene);
      L.scene->controller.hop_height = hop_height;
      L.pd = std::make_unique<control::PdBodyController>(
          L.scene->controller, scene.gravity, scene.legs.length, !scene.legs.body_only, false,
          L.scene->pulse.mode == scene::PulseMode::kDuration ? L.scene->pulse.duration : 0.0);
      L.rebound = std::make_unique<SpringReboundController>(
          *L.pd, scene.body.mass, &data.common_push, mean_hip, scene.gravity, &data.spring_stance,
          &data.hop_trim);
      L.legs = control::make_leg_controller(*L.scene);
      L.from = from;
      layers_.push_back(std::move(L));
    };
    add_layer(0.0, scene.controller.hop_height);
    for (const auto& [time, h] : scene.controller.hop_height_changes) add_layer(time, h);
  }
  /// The hop height asked at time t [m].
  double hop_height(double time) const { return at(time).scene->controller.hop_height; }
  /// The stance context at time t: with the spring legs' rebound layer, or the total
  /// request (leg placement).
  control::StanceContext context(double time, bool total) const {
    const Layer& L = at(time);
    const control::BodyController& b =
        spring_legs_ && !total ? static_cast<const control::BodyController&>(*L.rebound) : *L.pd;
    return control::StanceContext{*L.scene, b, *L.legs};
  }

 private:
  struct Layer {
    std::unique_ptr<scene::Scene> scene;
    std::unique_ptr<control::PdBodyController> pd;
    std::unique_ptr<SpringReboundController> rebound;
    std::unique_ptr<control::LegController> legs;
    double from = 0.0;  ///< in use from this time on [s]
  };
  const Layer& at(double time) const {
    size_t k = 0;
    while (k + 1 < layers_.size() && layers_[k + 1].from <= time) ++k;
    return layers_[k];
  }
  bool spring_legs_;
  std::vector<Layer> layers_;
};

/// One robot run on the hybrid loop: flight, stance and (spring legs) armed segments;
/// touchdown (the controller plans the stance and commands the actuators), the bottom of a
/// spring stance (the actuators fire), apex (hip placement, hop-height feedback), feet
/// landing and lifting off (free stance hips), actuators switching off, disturbances,
/// falls and energy blow-up.
class RobotRun final : public run::HybridModel {
 public:
  enum { kTouchdown = 0, kApex = 1, kFallLow = 2, kFallTilt = 3, kBottom = 4, kFoot = 5 };

  RobotRun(const scene::Scene& scene, const RobotModel& model, const RobotRunOptions& options);

  /// The stepper's options (verlet's energy budget in joules).
  const ode::SolverOptions& solver() const { return solver_; }
  int dimension() const { return sys_.dimension(); }
  ode::ErrorNorm error_norm() const { return sys_.error_norm(); }
  ode::Vec initial_state() const { return model_.mechanism.initial_state(); }
  /// Before the run: a run starting in the air places its legs for the first touchdown.
  void prepare(ode::Vec& y) {
    if (model_.spring_legs && prs_.hip_rotation) place_legs(0.0, y);
  }
  /// The run's records at its end (t, y).
  void finish(double t, const ode::Vec& y, const ode::Stepper& stepper);
  /// A run the fixed-step rule refuses (reduced/run_limits.hpp): `diverged` at t = 0 with
  /// the reason, the initial sample kept.
  run::HybridEnd refuse(ode::Stepper& stepper, const ode::Vec& y0, std::string reason) {
    stepper.reset(sys_, 0.0, y0);
    start(stepper, y0);
    end_run(reduced::RunStatus::kDiverged, std::move(reason));
    return {0.0, y0};
  }

  const ode::OdeSystem& system() const override { return sys_; }
  const ode::SolverOptions& integration_options() const override { return prs_.solver; }
  void start(const ode::Stepper& stepper, const ode::Vec& y) override {
    observer_.start(stepper, y);
  }
  double segment_end(double) const override {
    double t_target = scene_.simulation.duration;
    if (next_disturbance_ < scene_.disturbances.size()) {
      t_target = std::min(t_target, scene_.disturbances[next_disturbance_].time);
    }
    if (run_.stance) {
      for (size_t i = 0; i < legs_; ++i) {
        if (data_.leg_force[i] != 0.0) t_target = std::min(t_target, data_.off_time[i]);
      }
    }
    return t_target;
  }
  std::span<const ode::EventFunction* const> events() const override {
    return data_.armed ? armed_events_ : run_.stance ? stance_events_ : flight_events_;
  }
  ode::StepObserver* observer() override { return &observer_; }
  void on_failure(const run::Segment& seg, const ode::Vec&, const ode::Stepper& st) override {
    end_run(reduced::RunStatus::kDiverged,
            run::failure_reason(seg, st, prs_.solver, step_note(st)));
  }
  run::Next on_segment_end(const run::Segment& seg, ode::Vec& y,
                           const ode::Stepper& stepper) override;
  void on_restart() override { observer_.restart(); }

  RobotRunResult result;

 private:
  const std::vector<int>& event_ids() const {
    return data_.armed ? armed_ids_ : run_.stance ? stance_ids_ : flight_ids_;
  }
  void end_run(reduced::RunStatus status, std::string reason) {
    result.run.status = status;
    result.run.reason = std::move(reason);
  }
  std::string step_note(const ode::Stepper& st) const {
    return divergence_note(solver_.method, st.h(), verlet_limit_);
  }
  Vector3d total_momentum(const ode::Vec& ys) const {
    Vector3d p = Vector3d::Zero();
    for (size_t j = 0; j < model_.mechanism.masses.size(); ++j) p += ys.segment<3>(6 * j + 3);
    return p;
  }
  /// Everything the legs and the ground gave since touchdown (gravity removed) [N s].
  Vector3d delivered(double t, const ode::Vec& y) const {
    return total_momentum(y) - p_touchdown_ +
           Vector3d(0, 0, total_mass_ * g_ * (t - current_.t_touchdown));
  }
  void finish_stride(double t_next) {
    if (!have_stride_) return;
    reduced::close_stride(current_, t_next);
    result.run.strides.push_back(current_);
    result.stride_actuator_force.push_back(data_.stride_force);
    result.stride_slip.push_back(run_.stride_slip);
    have_stride_ = false;
  }
  void set_actuators() { sys_.set_actuators(data_.leg_force, data_.push); }
  /// The body state the controller sees: position, roll and pitch offset by the integral
  /// actions.
  control::BodyState trimmed(control::BodyState s) const {
    s.position.head<2>() += data_.position_trim.head<2>();
    if (prs_.attitude_trim_gain > 0.0) {
      s.euler123.head<2>() += data_.attitude_trim;
      s.attitude = math::euler_to_quat(s.euler123, math::EulerSet::k123);
      s.rotation = s.attitude.toRotationMatrix();
    }
    return s;
  }
  void book_work(double e_before, const ode::Vec& y) {
    book_hip_work(result.monitors, msys_.energies(y).total() - e_before);
  }
  bool energy_ok(double t, const ode::Vec& y, const ode::Stepper& stepper);
  void on_apex(double t, ode::Vec& y);
  run::Next on_touchdown(double t, const ode::Vec& y);
  double command_actuators(const control::StancePlan& plan, double t);
  void on_bottom(double t, const ode::Vec& y);
  double energy_thrust(double t, const ode::Vec& y);
  void on_foot(size_t first, double t, ode::Vec& y);
  void lift_foot(size_t i, ode::Vec& y);
  run::Next on_time(double t, ode::Vec& y);
  void apply_disturbance(const scene::Disturbance& d, ode::Vec& y);
  void place_legs(double t, ode::Vec& y);
  std::vector<Vector3d> placement(double t, const ode::Vec& y, control::BodyState& s,
                                  Matrix3d& R_td) const;
  std::vector<double> level_rest_lengths(const control::BodyState& s, const Matrix3d& R_td,
                                         const std::vector<Vector3d>& u) const;

  const scene::Scene& scene_;
  const RobotModel& model_;
  const scene::PseudoRigid& prs_;
  const size_t legs_;
  const double g_, l_;
  RunData data_;
  RobotSystem sys_;
  const pr::MechanismSystem& msys_;
  const ControlLayers control_;
  Run run_;
  Observer observer_;
  ComHeightEvent touchdown_, fall_low_;
  ApexEvent apex_;
  TiltEvent fall_tilt_;
  BottomEvent bottom_;
  std::vector<std::unique_ptr<FootEvent>> foot_events_;
  std::vector<const ode::EventFunction*> flight_events_, stance_events_, armed_events_;
  std::vector<int> flight_ids_, stance_ids_, armed_ids_;
  /// Rotating hips are driven in flight (they place the legs) and free about their
  /// pitch axis in stance: a landed foot's slide (a line) becomes a slot (a bilateral
  /// plane through the hip containing the leg and the body x axis), so the leg swings
  /// fore-aft over its gripped foot as a strut (spring, damper and actuator along the
  /// hip-foot line) while ab/adduction stays held; at lift-off the slide takes the
  /// leg again along its current direction. (Fully free hips, no slot, were tried:
  /// the four pinned struts make yaw unstable, ~3x per stride.)
  const bool free_stance_;
  double total_mass_ = 0.0, balance0_ = 0.0, blowup_ = 0.0;
  ode::SolverOptions solver_;
  double verlet_limit_ = 0.0;

  reduced::StrideRecord current_;
  bool have_stride_ = false;
  long touchdowns_ = 0, touchdown_events_ = 0;
  Vector3d p_touchdown_ = Vector3d::Zero();
  size_t next_disturbance_ = 0;
};

RobotRun::RobotRun(const scene::Scene& scene, const RobotModel& model,
                   const RobotRunOptions& options)
    : scene_(scene),
      model_(model),
      prs_(scene.pseudo_rigid),
      legs_(model.hip.size()),
      g_(scene.gravity),
      l_(scene.legs.length),
      data_(model, scene),
      sys_(model, data_.inputs, prs_),
      msys_(sys_.mechanism()),
      control_(scene, model, data_),
      run_(scene, model, sys_, msys_, result),
      observer_(run_, scene.simulation.sample_interval, sys_.dimension(),
                prs_.solver.method == ode::Method::kVerlet && sys_.has_dissipation_split()),
      touchdown_(model, l_),
      fall_low_(model, scene.simulation.fall_min_height),
      apex_(model),
      fall_tilt_(model, msys_, scene.simulation.fall_max_tilt),
      bottom_(model),
      flight_events_{&touchdown_, &apex_, &fall_low_, &fall_tilt_},
      stance_events_{&apex_, &fall_low_, &fall_tilt_},
      armed_events_{&bottom_, &fall_low_, &fall_tilt_},
      flight_ids_{kTouchdown, kApex, kFallLow, kFallTilt},
      stance_ids_{kApex, kFallLow, kFallTilt},
      armed_ids_{kBottom, kFallLow, kFallTilt},
      free_stance_(model.spring_legs && prs_.hip_rotation) {
  run_.record = options.record_trajectory;
  run_.in_contact.assign(legs_, false);
  run_.contact_start.assign(legs_, Eigen::Vector2d::Zero());
  if (free_stance_) {
    for (size_t i = 0; i < legs_; ++i) {
      foot_events_.push_back(std::make_unique<FootEvent>(sys_, i, model.foot[i]));
      for (auto* list : {&flight_events_, &stance_events_, &armed_events_}) {
        list->push_back(foot_events_.back().get());
      }
      for (auto* list : {&flight_ids_, &stance_ids_, &armed_ids_}) {
        list->push_back(kFoot + static_cast<int>(i));
      }
    }
  }
  const pr::Mechanism& mech = model.mechanism;
  RobotMonitors& mon = result.monitors;
  mon.internal_stiffness = mech.connections.empty() ? 0.0 : mech.connections.front().stiffness;
  if (sys_.rotation_state() >= 0) {  // rigid body: no internal springs; the leg slides' stiffness
    mon.internal_stiffness =
        model.slide.empty() || model.slide[0] < 0 ? 0.0 : mech.surfaces[model.slide[0]].stiffness;
  }
  mon.contact_stiffness = model.ground >= 0 ? mech.surfaces[model.ground].stiffness : 0.0;
  mon.stiffness = model.stiffness;
  total_mass_ = mech.total_mass();
  mon.energy_scale =
      total_mass_ * g_ * (std::max(0.0, scene.initial.position.z()) + scene.controller.hop_height);
  balance0_ = msys_.energies(mech.initial_state()).total();
  blowup_ = mech.simulation.energy_blowup_factor * mon.energy_scale;
  run_.balance0 = balance0_;
  run_.blowup = blowup_;
  solver_ = solver_options(prs_, mon.energy_scale);
  verlet_limit_ =
      solver_.method == ode::Method::kVerlet ? 2.0 / pr::max_frequency_bound(mech) : 0.0;
}

run::Next RobotRun::on_segment_end(const run::Segment& seg, ode::Vec& y,
                                   const ode::Stepper& stepper) {
  const double t = seg.t;
  {
    // The crawl guard over the whole run: events that fire again and again (a foot
    // chattering at a contact switch) restart integrate() before its own guard trips.
    const ode::SolverCounters& c = stepper.counters();
    const long attempts = c.steps_accepted + c.steps_rejected;
    if (prs_.solver.crawling(attempts, t)) {
      end_run(reduced::RunStatus::kDiverged, prs_.solver.crawl_reason(attempts, t, t));
      return run::Next::kStop;
    }
  }
  if (!energy_ok(t, y, stepper)) return run::Next::kStop;
  const int event = seg.event() >= 0 ? event_ids()[static_cast<size_t>(seg.event())] : -1;
  switch (event) {
    case kFallLow:
      end_run(reduced::RunStatus::kFell, reduced::fell_low_reason(scene_, t));
      return run::Next::kStop;
    case kFallTilt:
      end_run(reduced::RunStatus::kFell, reduced::tilted_reason(scene_, t));
      return run::Next::kStop;
    case kApex:
      on_apex(t, y);
      return run::Next::kContinue;
    case kTouchdown:
      return on_touchdown(t, y);
    case kBottom:
      on_bottom(t, y);
      return run::Next::kContinue;
    case -1:
      return on_time(t, y);
    default:
      on_foot(static_cast<size_t>(event - kFoot), t, y);
      return run::Next::kContinue;
  }
}

/// The energy balance at a segment's end (or at a sample on the way that blew up first):
/// false ends the run as diverged.
bool RobotRun::energy_ok(double t, const ode::Vec& y, const ode::Stepper& stepper) {
  const double balance =
      msys_.energies(y).total() + run_.dissipated - run_.work - result.monitors.hip_work;
  double drift = std::abs(balance - balance0_);
  double t_blowup = t;
  if (run_.blowup_time >= 0.0) {  // a sample on the way blew up first
    drift = run_.blowup_drift;
    t_blowup = run_.blowup_time;
  }
  if (!y.allFinite() || !std::isfinite(balance) || !(drift <= blowup_)) {
    // (The factor is named when the scene changed it from its default.)
    const double factor = model_.mechanism.simulation.energy_blowup_factor;
    const std::string set_factor = factor != scene::PseudoRigid{}.energy_blowup_factor
                                       ? ", energy_blowup_factor " + run::fmt(factor)
                                       : std::string();
    end_run(reduced::RunStatus::kDiverged,
            "energy blow-up at t = " + run::fmt(t_blowup) + " s: the balance drifted by " +
                run::fmt(drift) + " J (scale " + run::fmt(result.monitors.energy_scale) + " J" +
                set_factor + "); stiffness too high for the solver or the step too large" +
                step_note(stepper));
    return false;
  }
  result.monitors.energy_drift =
      std::max({result.monitors.energy_drift, drift, run_.sampled_drift});
  return true;
}

void RobotRun::on_apex(double t, ode::Vec& y) {
  if (!run_.stance && have_stride_ && !current_.has_apex) {
    current_.has_apex = true;
    current_.apex_height = body_com(model_, y).x.z();
    const double h = control_.hop_height(t);
    if (prs_.hop_trim_gain > 0.0 && prs_.thrust == scene::PseudoRigid::Thrust::kEnergy) {
      // The energy thrust's feedback: the apex it missed, asked for on top next time.
      data_.apex_trim =
          std::clamp(data_.apex_trim + prs_.hop_trim_gain * (l_ + h - current_.apex_height), -h,
                     prs_.hop_trim_max * h);
    } else if (prs_.hop_trim_gain > 0.0) {
      // Hop-height feedback: the takeoff speed this apex lacked, asked for next time.
      const double v_want = std::sqrt(2.0 * g_ * control_.hop_height(t));
      const double v_got = std::sqrt(2.0 * g_ * std::max(0.0, current_.apex_height - l_));
      data_.hop_trim = std::clamp(data_.hop_trim + prs_.hop_trim_gain * (v_want - v_got), -v_want,
                                  prs_.hop_trim_max * v_want);
    }
    current_.P_delivered = delivered(t, y);
  }
  if (!run_.stance && model_.spring_legs) {
    // Foot vibration on the leg springs (free fall: the springs would be at rest).
    const Com c = body_com(model_, y);
    double e = msys_.energies(y).leg;
    for (int f : model_.foot) {
      const double m = model_.mechanism.masses[f].mass;
      const Vector3d v = y.segment<3>(6 * f + 3) / m - c.v;
      e += 0.5 * m * v.squaredNorm();
    }
    result.monitors.max_leg_vibration_energy =
        std::max(result.monitors.max_leg_vibration_energy, e);
  }
  if (!run_.stance && model_.spring_legs && prs_.hip_rotation) place_legs(t, y);
}

run::Next RobotRun::on_touchdown(double t, const ode::Vec& y) {
  finish_stride(t);
  ++touchdown_events_;
  if (touchdowns_ >= scene_.simulation.max_strides) return run::Next::kStop;
  const control::BodyState s = run_.body_state(y);
  if (prs_.position_trim_gain > 0.0) {
    const Vector3d x_d =
        scene_.controller.setpoint_position + scene_.controller.setpoint_velocity * t;
    for (int k = 0; k < 2; ++k) {
      data_.position_trim[k] = std::clamp(
          data_.position_trim[k] + prs_.position_trim_gain * (s.position[k] - x_d[k]), -0.5, 0.5);
    }
  }
  if (prs_.attitude_trim_gain > 0.0) {
    for (int k = 0; k < 2; ++k) {
      data_.attitude_trim[k] =
          std::clamp(data_.attitude_trim[k] + prs_.attitude_trim_gain * s.euler123[k], -0.2, 0.2);
    }
  }
  const control::StancePlan plan =
      control::plan_stance(control_.context(t, false), touchdowns_, t, trimmed(s));
  current_ = reduced::open_stride(touchdowns_++, t, s, plan, scene_, result.run.warnings);
  // The stance attitude feedback holds the tilt that the integral action has learnt.
  sys_.set_stance_tilt(-data_.attitude_trim);
  have_stride_ = true;
  run_.stride_slip = 0.0;
  p_touchdown_ = total_momentum(y);
  const double stance_end = command_actuators(plan, t);
  data_.stride_force = data_.leg_force;
  current_.stance_duration = stance_end - t;
  run_.stance = stance_end > t;
  if (run_.stance && model_.spring_legs) {
    data_.armed = true;  // fire at the bottom of the stance
    std::fill(data_.leg_force.begin(), data_.leg_force.end(), 0.0);
  }
  set_actuators();
  return run::Next::kContinue;
}

/// Leg controllers: a constant force along each leg for the stance duration T; with a
/// force limit the pulse saturates, and with impulse feedback the actuator stays on until
/// its delivered impulse reaches the allocation (seed 5.4). Sets the legs' forces and
/// switch-off times and the stride's peak force and angular impulse; returns the stance's
/// end [s].
double RobotRun::command_actuators(const control::StancePlan& plan, double t) {
  const double T = prs_.actuators ? plan.duration : 0.0;
  double stance_end = t;
  Vector3d H = Vector3d::Zero();
  double peak = 0.0;
  std::fill(data_.leg_force.begin(), data_.leg_force.end(), 0.0);
  std::fill(data_.armed_force.begin(), data_.armed_force.end(), 0.0);
  for (size_t i = 0; i < legs_ && T > 0.0 && i < plan.leg_impulse.size(); ++i) {
    const Vector3d p = plan.leg_impulse[i];
    double impulse = 0.0;  // signed along the push direction [N s]
    if (model_.spring_legs) {
      impulse = p.dot(data_.push[i]);
    } else if (p.norm() > 0.0) {
      data_.push[i] = p.normalized();
      impulse = p.norm();
    }
    if (impulse == 0.0) continue;
    double f = impulse / T, duration = T;
    if (prs_.actuator_max_force > 0.0 && std::abs(f) > prs_.actuator_max_force) {
      f = std::copysign(prs_.actuator_max_force, f);
      if (prs_.impulse_feedback) {
        // The leg measures the net impulse it gives the body (its force minus its
        // share s of the weight it was compensating for, shares in proportion to
        // the legs' impulses) and stays on until that reaches its allocation net of
        // compensation: F_max T' - s T' = p - s T.
        double sum = 0.0;
        for (const auto& q : plan.leg_impulse) sum += q.norm();
        const double share =
            sum > 0.0 ? plan.gravity_compensation / T * std::abs(impulse) / sum : 0.0;
        const double net_rate = prs_.actuator_max_force - share;
        duration = net_rate > 0.0 ? (std::abs(impulse) - share * T) / net_rate
                                  : std::abs(impulse) / prs_.actuator_max_force;
      }
      ++result.run.warnings["actuator_saturated"];
    }
    data_.leg_force[i] = f;
    data_.off_time[i] = t + duration;
    data_.armed_force[i] = f;
    data_.armed_duration[i] = duration;
    stance_end = std::max(stance_end, data_.off_time[i]);
    peak = std::max(peak, std::abs(f));
    H += model_.hip[i].cross(f * duration * data_.push[i]);
  }
  current_.peak_leg_force = peak;
  current_.H_delivered = H;
  return stance_end;
}

/// The bottom of a spring stance: the armed actuators fire.
void RobotRun::on_bottom(double t, const ode::Vec& y) {
  data_.armed = false;
  double stance_end = t;
  if (prs_.thrust == scene::PseudoRigid::Thrust::kEnergy) {
    stance_end = energy_thrust(t, y);
  } else {
    for (size_t i = 0; i < legs_; ++i) {
      data_.leg_force[i] = data_.armed_force[i];
      data_.off_time[i] = t + data_.armed_duration[i];
      if (data_.leg_force[i] != 0.0) stance_end = std::max(stance_end, data_.off_time[i]);
    }
  }
  if (have_stride_) current_.stance_duration = stance_end - current_.t_touchdown;
  set_actuators();
}

/// The energy thrust (PseudoRigid::Thrust::kEnergy) at the bottom of the stance. The grounded
/// legs' springs and dampers lumped vertically give the collective vertical force that reaches
/// the target apex (thrust_law.hpp), held to the predicted lift-off. It is shared among the
/// grounded legs (share_thrust) so that their total moment about the CoM (roll, pitch) is the
/// planned one: the plan's differential impulses spread over the same time; the collective
/// itself, on legs that lean, adds none. Returns the stance's end [s].
double RobotRun::energy_thrust(double t, const ode::Vec& y) {
  const Vector3d com = body_com(model_, y).x;
  std::fill(data_.leg_force.begin(), data_.leg_force.end(), 0.0);
  std::vector<size_t> on;
  std::vector<Vector3d> u, arm;
  double K = 0.0, C = 0.0, s_v = 0.0, f_mean = 0.0;
  for (size_t i = 0; i < legs_; ++i) {
    if (data_.armed_force[i] == 0.0 || model_.leg_spring[i] < 0) continue;
    const Vector3d foot = y.segment<3>(6 * model_.foot[i]);
    const Vector3d hip = msys_.node_position(model_.hip_node[i], y);
    const Vector3d leg = hip - foot;
    if (foot.z() > kFootLift || !(leg.z() > 0.1 * leg.norm())) continue;  // not pushing up
    const double dz = leg.z() / leg.norm();
    const double rest = data_.inputs.rest_length[static_cast<size_t>(model_.leg_spring[i])];
    K += prs_.leg_stiffness * dz * dz;
    C += prs_.leg_damping * dz * dz;
    s_v += (rest - leg.norm()) * dz;
    f_mean += data_.armed_force[i];
    on.push_back(i);
    u.push_back(leg.normalized());
    arm.push_back(hip - com);
  }
  const size_t n = on.size();
  if (n == 0) return t;
  f_mean /= static_cast<double>(n);
  ThrustModel m;
  m.mass = scene_.body.mass;
  m.gravity = g_;
  m.stiffness = K;
  m.damping = C;
  m.z_bottom = com.z();
  m.z_rest = com.z() + s_v / static_cast<double>(n);
  double dz_sum = 0.0;
  for (const Vector3d& d : u) dz_sum += d.z();
  const double f_max =
      prs_.actuator_max_force > 0.0 ? prs_.actuator_max_force * dz_sum : 20.0 * m.mass * g_;
  const double apex = l_ + control_.hop_height(t) + data_.apex_trim;
  const ThrustPlan plan = plan_thrust(m, apex, -0.5 * K * (m.z_rest - m.z_bottom), f_max);
  if (plan.saturated) ++result.run.warnings["thrust_saturated"];
  const double T = std::max(plan.duration, 1e-6);
  std::vector<double> planned(n);
  for (size_t k = 0; k < n; ++k) {
    planned[k] = (data_.armed_force[on[k]] - f_mean) * data_.armed_duration[on[k]] / T;
  }
  const std::vector<double> f = share_thrust(plan.force, u, arm, planned);
  for (size_t k = 0; k < n; ++k) {
    data_.leg_force[on[k]] = f[k];
    data_.off_time[on[k]] = t + T;
  }
  data_.stride_force = data_.leg_force;
  current_.peak_leg_force = 0.0;
  for (double fi : data_.leg_force) {
    current_.peak_leg_force = std::max(current_.peak_leg_force, std::abs(fi));
  }
  return t + T;
}

/// A foot lands (its hip is freed in pitch) or lifts off (its slide takes the leg along
/// the leg's current direction; the foot's velocity across the line is the hip's to catch).
/// Energy changes are booked as hip work. Feet that crossed together (a symmetric landing)
/// switch together: an event fires only once.
void RobotRun::on_foot(size_t first, double t, ode::Vec& y) {
  const double e_before = msys_.energies(y).total();
  auto any_free = [&] {
    bool any = false;
    for (size_t k = 0; k < legs_; ++k) any = any || sys_.free(k);
    return any;
  };
  const bool was_free = any_free();
  for (size_t i = 0; i < legs_; ++i) {
    const double z = y[6 * model_.foot[i] + 2];
    const bool land = i == first ? !sys_.free(i) : !sys_.free(i) && z <= 0.0;
    const bool lift = i == first ? sys_.free(i) : sys_.free(i) && z >= kFootLift;
    pr::SurfaceInputs& slide = data_.inputs.surfaces[model_.slide[i]];
    if (land) {
      // The hip turns freely about its pitch axis: the foot is held in the plane of
      // the leg and the body x axis (a slot), so the leg swings fore-aft but not
      // sideways (ab/adduction held).
      const Vector3d nrm = slide.direction.cross(Vector3d::UnitX());
      if (nrm.norm() > 1e-6) {
        slide.type = pr::SurfaceType::kPlane;
        slide.bilateral = true;
        slide.direction = nrm.normalized();
      } else {
        slide.holds = false;
      }
      sys_.set_free(i, true);
    } else if (lift) {
      lift_foot(i, y);
    }
  }
  const bool now_free = any_free();
  if (now_free && !was_free) run_.contact_begin = t;
  if (!now_free && was_free) data_.spring_stance = t - run_.contact_begin;
  set_actuators();
  book_work(e_before, y);
}

/// Foot i lifts off: its slide (a line again) takes the leg along its current direction,
/// the foot's velocity across it removed.
void RobotRun::lift_foot(size_t i, ode::Vec& y) {
  const int foot = model_.foot[i];
  pr::SurfaceInputs& slide = data_.inputs.surfaces[model_.slide[i]];
  const pr::BodyFrame f = msys_.frames(y)[model_.body];
  const Vector3d w = msys_.body_omega(model_.body, y);
  const pr::NodeRef ghost{pr::NodeRef::Kind::kGhost,
                          model_.mechanism.surfaces[model_.slide[i]].ghost};
  const Vector3d xf = y.segment<3>(6 * foot);
  const Vector3d arm = xf - msys_.node_position(ghost, y);
  if (arm.norm() > 1e-9) {
    const double m = model_.mechanism.masses[foot].mass;
    const Vector3d d = arm.normalized();
    const Vector3d vb = f.com_velocity + w.cross(xf - f.com);
    const Vector3d vrel = y.segment<3>(6 * foot + 3) / m - vb;
    y.segment<3>(6 * foot + 3) = m * (vb + vrel.dot(d) * d);
    slide.direction = f.rotation.transpose() * d;
    data_.push[i] = -slide.direction;
  }
  slide.type = pr::SurfaceType::kLine;
  slide.bilateral = false;
  slide.holds = true;
  sys_.set_free(i, false);
}

/// Reached the segment's end: an actuator switching off, a disturbance, or the end.
run::Next RobotRun::on_time(double t, ode::Vec& y) {
  if (run_.stance && !data_.armed) {
    bool on = false;
    for (size_t i = 0; i < legs_; ++i) {
      double& f = data_.leg_force[i];
      if (f != 0.0 && data_.off_time[i] <= t * (1.0 + 1e-14) + 1e-14) f = 0.0;
      on = on || f != 0.0;
    }
    set_actuators();
    run_.stance = on;
  }
  while (next_disturbance_ < scene_.disturbances.size() &&
         scene_.disturbances[next_disturbance_].time <= t) {
    apply_disturbance(scene_.disturbances[next_disturbance_++], y);
  }
  return t >= scene_.simulation.duration ? run::Next::kStop : run::Next::kContinue;
}

/// Linear impulse shared by the four body masses; angular impulse as the rigid velocity
/// change dw = I^-1 H (body frame). Its energy is booked as external work.
void RobotRun::apply_disturbance(const scene::Disturbance& d, ode::Vec& y) {
  const pr::BodyFrame f = msys_.frames(y)[model_.body];
  const Vector3d dw = f.rotation * (scene_.body.inertia.inverse() * d.angular_impulse);
  const auto& b = model_.mechanism.bodies[model_.body];
  const double e_before = msys_.energies(y).total();
  const int rot = sys_.rotation_state();
  if (rot >= 0) {  // rigid body: dp on its CoM mass, dL = R H
    y.segment<3>(6 * b.first_mass + 3) += d.linear_impulse;
    y.segment<3>(rot + 4) += f.rotation * d.angular_impulse;
  }
  for (int k = 0; k < (rot >= 0 ? 0 : 4); ++k) {
    const int j = b.first_mass + k;
    const Vector3d arm = y.segment<3>(6 * j) - f.com;
    y.segment<3>(6 * j + 3) +=
        0.25 * d.linear_impulse + model_.mechanism.masses[j].mass * dw.cross(arm);
  }
  book_work(e_before, y);
}

/// Hip placement (hip_rotation): plan the stance at the predicted (ballistic) touchdown and
/// turn each leg in the air along its total impulse; the foot moves with the leg (its
/// energy change is hip work).
void RobotRun::place_legs(double t, ode::Vec& y) {
  control::BodyState s = trimmed(run_.body_state(y));
  if (!(s.position.z() - l_ > 0.0)) return;
  Matrix3d R_td;
  const std::vector<Vector3d> u = placement(t, y, s, R_td);
  const std::vector<double> rest = level_rest_lengths(s, R_td, u);
  const double e_before = msys_.energies(y).total();
  const pr::BodyFrame f = msys_.frames(y)[model_.body];
  const Vector3d w = msys_.body_omega(model_.body, y);
  for (size_t i = 0; i < legs_; ++i) {
    if (sys_.free(i)) continue;  // still on the ground
    const int foot = model_.foot[i];
    const double m = model_.mechanism.masses[foot].mass;
    const pr::NodeRef ghost{pr::NodeRef::Kind::kGhost,
                            model_.mechanism.surfaces[model_.slide[i]].ghost};
    const Vector3d hip = msys_.node_position(ghost, y);
    const Vector3d d_old = f.rotation * (-data_.push[i]);
    const Vector3d d_new = f.rotation * u[i];
    const Vector3d xf = y.segment<3>(6 * foot);
    // (the spring keeps its deflection when its rest length changes)
    double& rest_now = data_.inputs.rest_length[static_cast<size_t>(model_.leg_spring[i])];
    const double ext = (xf - hip).dot(d_old) + rest[i] - rest_now;
    rest_now = rest[i];
    const Vector3d vrel = y.segment<3>(6 * foot + 3) / m - (f.com_velocity + w.cross(xf - f.com));
    const Vector3d xn = hip + ext * d_new;
    const Vector3d vn = f.com_velocity + w.cross(xn - f.com) + vrel.dot(d_old) * d_new;
    y.segment<3>(6 * foot) = xn;
    y.segment<3>(6 * foot + 3) = m * vn;
    data_.inputs.surfaces[model_.slide[i]].direction = u[i];
    data_.push[i] = -u[i];
  }
  data_.common_push = -u[0];  // (a leg still on the ground keeps its direction)
  book_work(e_before, y);
}

/// The legs' directions (body frame, unit hip -> foot) for the stance planned at the
/// predicted ballistic touchdown; s becomes the predicted touchdown state, R_td the body
/// attitude then (after the flight at constant angular velocity).
std::vector<Vector3d> RobotRun::placement(double t, const ode::Vec& y, control::BodyState& s,
                                          Matrix3d& R_td) const {
  const double tf = std::sqrt(2.0 * (s.position.z() - l_) / g_);
  const Vector3d w_world = msys_.body_omega(model_.body, y);
  R_td = msys_.frames(y)[model_.body].rotation;
  if (w_world.norm() * tf > 1e-12) {
    R_td = Eigen::AngleAxisd(w_world.norm() * tf, w_world.normalized()) * R_td;
  }
  s.position += s.velocity * tf + Vector3d(0, 0, -0.5 * g_ * tf * tf);
  s.velocity.z() -= g_ * tf;
  const control::StancePlan pred =
      control::plan_stance(control_.context(t + tf, true), touchdowns_, t + tf, s);
  if (!free_stance_) return leg_directions(pred, legs_, prs_.max_leg_angle);
  // The legs' total push plus the weight carried over the stance, placed in
  // the world and turned into the body frame the body will have at touchdown.
  Vector3d P = pred.command.P_world;
  P.z() += total_mass_ * g_ * data_.spring_stance;
  // The hips' mean speed over the stance: the CoM's plus half the change asked.
  const Vector3d v_mean = s.velocity + 0.5 * pred.command.P_world / total_mass_;
  const bool held_roll = prs_.stance_kp[0] > 0.0 || prs_.stance_kd[0] > 0.0;
  // Desired takeoff velocity: lateral as the controller asks, vertical as the
  // springs return it (the touchdown speed).
  Vector3d v_takeoff = s.velocity + pred.command.P_world / total_mass_;
  v_takeoff.z() = std::max(-s.velocity.z(), 0.1);
  const Vector3d d = free_leg_direction(P, v_mean, data_.spring_stance, model_.rest_length[0],
                                        prs_.max_leg_angle, held_roll, v_takeoff);
  return std::vector<Vector3d>(legs_, R_td.transpose() * d);
}

/// Level feet: each leg's rest length such that every foot reaches the ground together at
/// the predicted touchdown attitude R_td (CoM at s.position); the current ones otherwise.
std::vector<double> RobotRun::level_rest_lengths(const control::BodyState& s, const Matrix3d& R_td,
                                                 const std::vector<Vector3d>& u) const {
  std::vector<double> rest(legs_);
  for (size_t i = 0; i < legs_; ++i) {
    rest[i] = data_.inputs.rest_length[static_cast<size_t>(model_.leg_spring[i])];
  }
  if (!(prs_.level_feet && free_stance_)) return rest;
  double z_mean = 0.0;
  std::vector<double> hz(legs_), dz_leg(legs_);
  for (size_t i = 0; i < legs_; ++i) {
    hz[i] = s.position.z() + (R_td * model_.hip[i]).z();
    dz_leg[i] = (R_td * u[i]).z();
    z_mean += (hz[i] + model_.rest_length[i] * dz_leg[i]) / static_cast<double>(legs_);
  }
  for (size_t i = 0; i < legs_; ++i) {
    if (sys_.free(i) || !(dz_leg[i] < -0.1)) continue;
    rest[i] = std::clamp((z_mean - hz[i]) / dz_leg[i], 0.75 * model_.rest_length[i],
                         1.25 * model_.rest_length[i]);
  }
  return rest;
}

void RobotRun::finish(double t, const ode::Vec& y, const ode::Stepper& stepper) {
  reduced::RunResult& res = result.run;
  if (have_stride_ && !current_.has_apex) current_.P_delivered = delivered(t, y);
  finish_stride(-1.0);
  result.monitors.actuator_work = run_.work + result.monitors.hip_work;
  result.monitors.positive_actuator_work = run_.positive_work + result.monitors.positive_hip_work;
  reduced::finish_run(res, t, run_.body_state(y), touchdowns_, scene_);
  // Only finite samples are kept (a diverged run keeps what came before).
  while (!res.trajectory.empty() && !(res.trajectory.back().position.allFinite() &&
                                      std::isfinite(result.samples.back().energies.total()))) {
    res.trajectory.pop_back();
    result.samples.pop_back();
  }
  auto finite_or = [](double& x) {
    if (!std::isfinite(x)) x = 1e300;
  };
  finite_or(result.monitors.energy_drift);
  finite_or(result.monitors.max_strain);
  finite_or(result.monitors.max_penetration);
  finite_or(result.monitors.max_slip);
  if (!res.final_position.allFinite()) {
    res.final_position.setZero();
    res.final_velocity.setZero();
    res.final_euler123.setZero();
    res.final_omega.setZero();
  }
  result.monitors.zero_length_triggers = msys_.zero_length_triggers();
  res.cost.solver = stepper.counters();
  res.cost.touchdowns = touchdown_events_;
}

}  // namespace

namespace {

/// Auto's choice written into the scene's solver settings and the built model's solver.
void apply_to_scene(const pr::MethodChoice& c, scene::Scene* scene, RobotModel* model) {
  scene::PseudoRigid& p = scene->pseudo_rigid;
  pr::apply_choice(c, &p.solver, &p.energy_tol);
  p.solver_auto = false;
  model->mechanism.simulation.solver = p.solver;
}

/// "method": "auto": the scene with the method chosen for its built robot (model's solver
/// updated as build_robot sets it); the choice in *choice.
scene::Scene with_chosen_method(const scene::Scene& scene, RobotModel* model,
                                pr::MethodChoice* choice) {
  scene::Scene chosen = scene;
  scene::PseudoRigid& p = chosen.pseudo_rigid;
  pr::AutoRequest request;
  request.accuracy = p.accuracy;
  request.h_max = p.solver.h_max;
  request.t_end = scene.simulation.duration;
  request.restarts = true;  // touchdowns, apexes, foot switches
  *choice = pr::choose_method(model->mechanism, request);
  apply_to_scene(*choice, &chosen, model);
  return chosen;
}

/// One run of the built robot on the scene's solver.
RobotRunResult run_once(const scene::Scene& scene, const RobotModel& model,
                        const RobotRunOptions& options, bool automatic,
                        const pr::MethodChoice& choice) {
  auto robot = std::make_unique<RobotRun>(scene, model, options);
  robot->result.monitors.method_auto = automatic;
  robot->result.monitors.method_choice = choice;
  auto stepper = ode::make_stepper(robot->solver(), robot->dimension(), robot->error_norm());
  ode::Vec y = robot->initial_state();
  robot->prepare(y);
  const auto too_long = reduced::fixed_step_breach(scene, robot->solver());
  const run::HybridEnd end = too_long ? robot->refuse(*stepper, y, too_long->reason())
                                      : run::run_hybrid(*robot, *stepper, 0.0, y);
  robot->finish(end.t, end.y, *stepper);
  return std::move(robot->result);
}

}  // namespace

RobotRunResult simulate(const scene::Scene& scene_in, const RobotRunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  reduced::require_memory_limits(scene_in.simulation, options.record_trajectory, true);
  RobotModel model = build_robot(scene_in);
  pr::MethodChoice choice;
  const bool automatic = scene_in.pseudo_rigid.solver_auto;
  scene::Scene chosen;  // the scene with auto's choice (no copy otherwise)
  if (automatic) chosen = with_chosen_method(scene_in, &model, &choice);
  RobotRunResult result =
      run_once(automatic ? chosen : scene_in, model, options, automatic, choice);
  // Auto checks its run: a completed run that missed the accuracy is rerun once, tighter
  // (method_choice.hpp, refine_choice); the cost reported is both runs'.
  if (automatic && result.run.status == reduced::RunStatus::kCompleted &&
      pr::needs_rerun(choice, result.monitors.drift_relative())) {
    choice = pr::refine_choice(choice, result.monitors.drift_relative());
    apply_to_scene(choice, &chosen, &model);
    const ode::SolverCounters first = result.run.cost.solver;
    result = run_once(chosen, model, options, automatic, choice);
    result.run.cost.solver += first;
  }
  result.run.cost.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace pronk::robot
