#include "sim/robot/robot_simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "sim/control/stance_planner.hpp"
#include "sim/math/rotation.hpp"
#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/pseudorigid/stability.hpp"
#include "sim/robot/robot_system.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

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

  std::vector<Vector3d> push;  ///< body-frame push direction of each actuator
};

// Energy put in (or taken out) by placing the legs [J].
void book_hip_work(RobotMonitors& m, double dE) {
  m.hip_work += dE;
  m.positive_hip_work += std::max(0.0, dE);
}

/// Energy flows, monitors and samples along the accepted steps. Method verlet books both
/// flows as its steps do: the dissipation is the stepper's own (OdeSystem::dissipate), the
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
      const double booked = st.booked_dissipation();
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
    booked_ = st.booked_dissipation();
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
  std::string note = " (" + std::string(ode::to_string(method)) + " step " + fmt(h) + " s";
  if (verlet_limit > 0.0) {
    note += "; verlet is stable below h = 2/omega_max >= " + fmt(verlet_limit) +
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

}  // namespace

RobotRunResult simulate(const scene::Scene& scene, const RobotRunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  RobotRunResult result;
  reduced::RunResult& res = result.run;
  const RobotModel model = build_robot(scene);
  pr::Mechanism mech = model.mechanism;  // this run's copy: hip placement turns the slides
  const scene::PseudoRigid& prs = scene.pseudo_rigid;
  RobotSystem sys(model, mech, prs);
  const pr::MechanismSystem& msys = sys.mechanism();
  const int n = sys.dimension();
  const size_t legs = model.hip.size();
  const double g = scene.gravity;
  const double l = scene.legs.length;
  const auto& sim = scene.simulation;

  // The same three control layers as the reduced models, planned as constant-force
  // pulses (the pulse settings); the spring legs' layer removes the rebound.
  scene::Scene plan_scene = scene;
  plan_scene.model = scene::ModelKind::kPulse;
  if (model.spring_legs) plan_scene.pulse.gravity_compensation = false;
  Vector3d common_push = Vector3d::UnitZ();  // legs' push direction, body frame
  Vector3d mean_hip = Vector3d::Zero();      // body frame [m]
  for (const Vector3d& h : model.hip) mean_hip += h / static_cast<double>(model.hip.size());
  // Expected stance duration of spring legs [s]: half a period of the body on its leg
  // springs until a stance is measured (free stance hips measure every stance).
  double spring_stance =
      model.spring_legs
          ? M_PI * std::sqrt(scene.body.mass /
                             (prs.leg_stiffness * static_cast<double>(model.hip.size())))
          : 0.0;
  double hop_trim = 0.0;  ///< hop-height feedback: extra takeoff speed asked [m/s]
  // One controller per hop-height setpoint (controller.hop_height_changes).
  struct Layer {
    std::unique_ptr<scene::Scene> scene;
    std::unique_ptr<control::PdBodyController> pd;
    std::unique_ptr<SpringReboundController> rebound;
    std::unique_ptr<control::LegController> legs;
    double from = 0.0;  ///< in use from this time on [s]
  };
  std::vector<Layer> layers;
  auto add_layer = [&](double from, double hop_height) {
    Layer L;
    L.scene = std::make_unique<scene::Scene>(plan_scene);
    L.scene->controller.hop_height = hop_height;
    L.pd = std::make_unique<control::PdBodyController>(
        L.scene->controller, g, l, !scene.legs.body_only, false,
        L.scene->pulse.mode == scene::PulseMode::kDuration ? L.scene->pulse.duration : 0.0);
    L.rebound = std::make_unique<SpringReboundController>(*L.pd, scene.body.mass, &common_push,
                                                          mean_hip, g, &spring_stance, &hop_trim);
    L.legs = control::make_leg_controller(*L.scene);
    L.from = from;
    layers.push_back(std::move(L));
  };
  add_layer(0.0, scene.controller.hop_height);
  for (const auto& [time, h] : scene.controller.hop_height_changes) add_layer(time, h);
  auto layer_at = [&](double time) -> const Layer& {
    size_t k = 0;
    while (k + 1 < layers.size() && layers[k + 1].from <= time) ++k;
    return layers[k];
  };
  // The stance context at time t: with the spring legs' rebound layer, or the total
  // request (leg placement).
  auto context = [&](double time, bool total) {
    const Layer& L = layer_at(time);
    const control::BodyController& b = model.spring_legs && !total
                                           ? static_cast<const control::BodyController&>(*L.rebound)
                                           : *L.pd;
    return control::StanceContext{*L.scene, b, *L.legs};
  };

  ode::Vec y = mech.initial_state();

  Run run{scene, model, sys, msys, result};
  run.record = options.record_trajectory;
  run.in_contact.assign(legs, false);
  run.contact_start.assign(legs, Eigen::Vector2d::Zero());
  run.push.assign(legs, Vector3d::UnitZ());
  for (size_t i = 0; i < legs; ++i) run.push[i] = -model.direction[i];
  Observer observer(run, sim.sample_interval, n,
                    prs.solver.method == ode::Method::kVerlet && sys.has_dissipation_split());

  ComHeightEvent touchdown(model, l);
  ApexEvent apex(model);
  ComHeightEvent fall_low(model, sim.fall_min_height);
  TiltEvent fall_tilt(model, msys, sim.fall_max_tilt);
  BottomEvent bottom(model);
  std::vector<const ode::EventFunction*> flight_events = {&touchdown, &apex, &fall_low, &fall_tilt};
  std::vector<const ode::EventFunction*> stance_events = {&apex, &fall_low, &fall_tilt};
  std::vector<const ode::EventFunction*> armed_events = {&bottom, &fall_low, &fall_tilt};
  enum { kTouchdown = 0, kApex = 1, kFallLow = 2, kFallTilt = 3, kBottom = 4, kFoot = 5 };
  std::vector<int> flight_ids = {kTouchdown, kApex, kFallLow, kFallTilt};
  std::vector<int> stance_ids = {kApex, kFallLow, kFallTilt};
  std::vector<int> armed_ids = {kBottom, kFallLow, kFallTilt};
  // Rotating hips are driven in flight (they place the legs) and free about their
  // pitch axis in stance: a landed foot's slide (a line) becomes a slot (a bilateral
  // plane through the hip containing the leg and the body x axis), so the leg swings
  // fore-aft over its gripped foot as a strut (spring, damper and actuator along the
  // hip-foot line) while ab/adduction stays held; at lift-off the slide takes the
  // leg again along its current direction. (Fully free hips, no slot, were tried:
  // the four pinned struts make yaw unstable, ~3x per stride.)
  const bool free_stance = model.spring_legs && prs.hip_rotation;
  std::vector<std::unique_ptr<FootEvent>> foot_events;
  if (free_stance) {
    for (size_t i = 0; i < legs; ++i) {
      foot_events.push_back(std::make_unique<FootEvent>(sys, i, model.foot[i]));
      for (auto* list : {&flight_events, &stance_events, &armed_events}) {
        list->push_back(foot_events.back().get());
      }
      for (auto* list : {&flight_ids, &stance_ids, &armed_ids}) {
        list->push_back(kFoot + static_cast<int>(i));
      }
    }
  }
  // Spring legs: the actuators fire in the thrust phase, from the bottom of the
  // stance (CoM velocity rising through zero) on, so a downward force lowers the
  // takeoff speed and an upward one raises it (seed fig. 2.13).
  bool armed = false;
  std::vector<double> armed_force(legs, 0.0), armed_duration(legs, 0.0);

  result.monitors.internal_stiffness =
      mech.connections.empty() ? 0.0 : mech.connections.front().stiffness;
  if (sys.rotation_state() >= 0) {  // rigid body: no internal springs; the leg slides' stiffness
    result.monitors.internal_stiffness =
        model.slide.empty() || model.slide[0] < 0 ? 0.0 : mech.surfaces[model.slide[0]].stiffness;
  }
  result.monitors.contact_stiffness =
      model.ground >= 0 ? mech.surfaces[model.ground].stiffness : 0.0;
  result.monitors.stiffness = model.stiffness;
  const double total_mass = mech.total_mass();
  result.monitors.energy_scale =
      total_mass * g * (std::max(0.0, scene.initial.position.z()) + scene.controller.hop_height);
  const double balance0 = msys.energies(y).total();
  const double blowup = 10.0 * result.monitors.energy_scale;
  run.balance0 = balance0;
  run.blowup = blowup;
  const ode::SolverOptions solver = solver_options(prs, result.monitors.energy_scale);
  auto stepper = ode::make_stepper(solver, n);
  const double verlet_limit =
      solver.method == ode::Method::kVerlet ? 2.0 / pr::max_frequency_bound(mech) : 0.0;
  auto step_note = [&]() { return divergence_note(solver.method, stepper->h(), verlet_limit); };

  auto end_run = [&](reduced::RunStatus status, std::string reason) {
    res.status = status;
    res.reason = std::move(reason);
  };
  auto total_momentum = [&](const ode::Vec& ys) {
    Vector3d p = Vector3d::Zero();
    for (size_t j = 0; j < mech.masses.size(); ++j) p += ys.segment<3>(6 * j + 3);
    return p;
  };

  reduced::StrideRecord current;
  bool have_stride = false;
  long touchdowns = 0, touchdown_events = 0;
  Vector3d p_touchdown = Vector3d::Zero();
  std::vector<double> leg_force(legs, 0.0), off_time(legs, 0.0);
  std::vector<double> stride_force(legs, 0.0);
  auto finish_stride = [&](double t_next) {
    if (!have_stride) return;
    if (t_next > current.t_touchdown) {
      current.stride_time = t_next - current.t_touchdown;
      current.duty_cycle = current.stance_duration / current.stride_time;
    }
    res.strides.push_back(current);
    result.stride_actuator_force.push_back(stride_force);
    result.stride_slip.push_back(run.stride_slip);
    have_stride = false;
  };

  // Hip placement (hip_rotation): plan the stance at the predicted (ballistic)
  // touchdown and turn each leg in the air to its placement; the foot moves with the
  // leg (its energy change is hip work).
  auto place_legs = [&](double t, ode::Vec& y) {
    // Hip placement: plan the stance at the predicted (ballistic) touchdown and turn
    // each leg along its total impulse; the foot moves with the leg (its energy
    // change is hip work).
    control::BodyState s = run.body_state(y);
    const double dz = s.position.z() - l;
    if (dz > 0.0) {
      const double tf = std::sqrt(2.0 * dz / g);
      // Body attitude at the predicted touchdown, after tf of free flight (constant
      // angular velocity).
      const Vector3d w_world = msys.body_omega(model.body, y);
      Matrix3d R_td = msys.frames(y)[model.body].rotation;
      if (w_world.norm() * tf > 1e-12) {
        R_td = Eigen::AngleAxisd(w_world.norm() * tf, w_world.normalized()) * R_td;
      }
      s.position += s.velocity * tf + Vector3d(0, 0, -0.5 * g * tf * tf);
      s.velocity.z() -= g * tf;
      const control::StancePlan pred =
          control::plan_stance(context(t + tf, true), touchdowns, t + tf, s);
      std::vector<Vector3d> u;
      if (free_stance) {
        // The legs' total push plus the weight carried over the stance, placed in
        // the world and turned into the body frame the body will have at touchdown.
        Vector3d P = pred.command.P_world;
        P.z() += total_mass * g * spring_stance;
        // The hips' mean speed over the stance: the CoM's plus half the change asked.
        const Vector3d v_mean = s.velocity + 0.5 * pred.command.P_world / total_mass;
        const bool held_roll = prs.stance_kp[0] > 0.0 || prs.stance_kd[0] > 0.0;
        // Desired takeoff velocity: lateral as the controller asks, vertical as the
        // springs return it (the touchdown speed).
        Vector3d v_takeoff = s.velocity + pred.command.P_world / total_mass;
        v_takeoff.z() = std::max(-s.velocity.z(), 0.1);
        const Vector3d d = free_leg_direction(P, v_mean, spring_stance, model.rest_length[0],
                                              prs.max_leg_angle, held_roll, v_takeoff);
        u.assign(legs, R_td.transpose() * d);
      } else {
        u = leg_directions(pred, legs, prs.max_leg_angle);
      }
      // Level feet: each leg's rest length such that every foot reaches the ground
      // together at the predicted touchdown attitude R_td (CoM at s.position).
      std::vector<double> rest(legs);
      for (size_t i = 0; i < legs; ++i) {
        rest[i] = mech.connections[static_cast<size_t>(model.leg_spring[i])].rest_length;
      }
      if (prs.level_feet && free_stance) {
        double z_mean = 0.0;
        std::vector<double> hz(legs), dz_leg(legs);
        for (size_t i = 0; i < legs; ++i) {
          hz[i] = s.position.z() + (R_td * model.hip[i]).z();
          dz_leg[i] = (R_td * u[i]).z();
          z_mean += (hz[i] + model.rest_length[i] * dz_leg[i]) / static_cast<double>(legs);
        }
        for (size_t i = 0; i < legs; ++i) {
          if (sys.free(i) || !(dz_leg[i] < -0.1)) continue;
          rest[i] = std::clamp((z_mean - hz[i]) / dz_leg[i], 0.75 * model.rest_length[i],
                               1.25 * model.rest_length[i]);
        }
      }
      const double e_before = msys.energies(y).total();
      const pr::BodyFrame f = msys.frames(y)[model.body];
      const Vector3d w = msys.body_omega(model.body, y);
      for (size_t i = 0; i < legs; ++i) {
        if (sys.free(i)) continue;  // still on the ground
        const int foot = model.foot[i];
        const pr::NodeRef ghost{pr::NodeRef::Kind::kGhost, mech.surfaces[model.slide[i]].ghost};
        const Vector3d hip = msys.node_position(ghost, y);
        const Vector3d d_old = f.rotation * (-run.push[i]);
        const Vector3d d_new = f.rotation * u[i];
        const Vector3d xf = y.segment<3>(6 * foot);
        // (the spring keeps its deflection when its rest length changes)
        double& rest_now = mech.connections[static_cast<size_t>(model.leg_spring[i])].rest_length;
        const double ext = (xf - hip).dot(d_old) + rest[i] - rest_now;
        rest_now = rest[i];
        const Vector3d vrel = y.segment<3>(6 * foot + 3) / mech.masses[foot].mass -
                              (f.com_velocity + w.cross(xf - f.com));
        const Vector3d xn = hip + ext * d_new;
        const Vector3d vn = f.com_velocity + w.cross(xn - f.com) + vrel.dot(d_old) * d_new;
        y.segment<3>(6 * foot) = xn;
        y.segment<3>(6 * foot + 3) = mech.masses[foot].mass * vn;
        mech.surfaces[model.slide[i]].direction = u[i];
        run.push[i] = -u[i];
      }
      common_push = -u[0];  // (a leg still on the ground keeps its direction)
      book_hip_work(result.monitors, msys.energies(y).total() - e_before);
    }
  };

  double t = 0.0;
  size_t next_disturbance = 0;
  // A run starting in the air places its legs for the first touchdown.
  if (model.spring_legs && prs.hip_rotation) place_legs(t, y);
  stepper->reset(sys, t, y);
  observer.start(*stepper, y);
  bool running = true;
  while (running) {
    double t_target = sim.duration;
    if (next_disturbance < scene.disturbances.size()) {
      t_target = std::min(t_target, scene.disturbances[next_disturbance].time);
    }
    if (run.stance) {
      for (size_t i = 0; i < legs; ++i) {
        if (leg_force[i] != 0.0) t_target = std::min(t_target, off_time[i]);
      }
    }
    std::span<const ode::EventFunction* const> events =
        armed        ? std::span<const ode::EventFunction* const>(armed_events)
        : run.stance ? std::span<const ode::EventFunction* const>(stance_events)
                     : std::span<const ode::EventFunction* const>(flight_events);
    const int* ids = armed ? armed_ids.data() : run.stance ? stance_ids.data() : flight_ids.data();
    ode::IntegrateResult r;
    if (t_target > t) {
      r = ode::integrate(sys, *stepper, t_target, events, prs.solver, &observer);
    } else {
      r.reason = ode::StopReason::kReachedEnd;
      r.t = t;
    }
    t = r.t;
    y = stepper->y();
    switch (r.reason) {
      case ode::StopReason::kStepSizeCollapse:
        end_run(reduced::RunStatus::kDiverged,
                "step-size collapse at t = " + fmt(t) + " s" + step_note());
        running = false;
        continue;
      case ode::StopReason::kNonFinite:
        end_run(reduced::RunStatus::kDiverged,
                "non-finite state at t = " + fmt(t) + " s" + step_note());
        running = false;
        continue;
      case ode::StopReason::kMaxSteps:
        end_run(reduced::RunStatus::kDiverged,
                prs.solver.step_limit_reason(
                    stepper->counters().steps_accepted + stepper->counters().steps_rejected, t));
        running = false;
        continue;
      case ode::StopReason::kCrawling:
        end_run(reduced::RunStatus::kDiverged,
                prs.solver.crawl_reason(r.attempts, t - r.t_start, t));
        running = false;
        continue;
      default:
        break;
    }
    {
      // The crawl guard over the whole run: events that fire again and again (a foot
      // chattering at a contact switch) restart integrate() before its own guard trips.
      const ode::SolverCounters& c = stepper->counters();
      const long attempts = c.steps_accepted + c.steps_rejected;
      if (prs.solver.crawling(attempts, t)) {
        end_run(reduced::RunStatus::kDiverged, prs.solver.crawl_reason(attempts, t, t));
        running = false;
        continue;
      }
    }
    const double balance =
        msys.energies(y).total() + run.dissipated - run.work - result.monitors.hip_work;
    double drift = std::abs(balance - balance0);
    double t_blowup = t;
    if (run.blowup_time >= 0.0) {  // a sample on the way blew up first
      drift = run.blowup_drift;
      t_blowup = run.blowup_time;
    }
    if (!y.allFinite() || !std::isfinite(balance) || !(drift <= blowup)) {
      end_run(reduced::RunStatus::kDiverged,
              "energy blow-up at t = " + fmt(t_blowup) + " s: the balance drifted by " +
                  fmt(drift) + " J (scale " + fmt(result.monitors.energy_scale) +
                  " J); stiffness too high for the solver or the step too large" + step_note());
      break;
    }
    result.monitors.energy_drift =
        std::max({result.monitors.energy_drift, drift, run.sampled_drift});
    const int event = r.reason == ode::StopReason::kEvent ? ids[r.event_index] : -1;
    if (event == kFallLow) {
      end_run(reduced::RunStatus::kFell,
              "CoM fell below " + fmt(sim.fall_min_height) + " m at t = " + fmt(t) + " s");
      break;
    }
    if (event == kFallTilt) {
      end_run(reduced::RunStatus::kFell, "body tilted past " + fmt(sim.fall_max_tilt * 180 / M_PI) +
                                             " deg at t = " + fmt(t) + " s");
      break;
    }
    if (event == kApex) {
      if (!run.stance && have_stride && !current.has_apex) {
        current.has_apex = true;
        current.apex_height = body_com(model, y).x.z();
        if (prs.hop_trim_gain > 0.0) {
          // Hop-height feedback: the takeoff speed this apex lacked, asked for next time.
          const double v_want = std::sqrt(2.0 * g * layer_at(t).scene->controller.hop_height);
          const double v_got = std::sqrt(2.0 * g * std::max(0.0, current.apex_height - l));
          hop_trim = std::clamp(hop_trim + prs.hop_trim_gain * (v_want - v_got), -v_want,
                                prs.hop_trim_max * v_want);
        }
        // Everything the legs and the ground gave since touchdown (gravity removed).
        current.P_delivered = total_momentum(y) - p_touchdown +
                              Vector3d(0, 0, total_mass * g * (t - current.t_touchdown));
      }
      if (!run.stance && model.spring_legs) {
        // Foot vibration on the leg springs (free fall: the springs would be at rest).
        const Com c = body_com(model, y);
        double e = msys.energies(y).leg;
        for (int f : model.foot) {
          const Vector3d v = y.segment<3>(6 * f + 3) / mech.masses[f].mass - c.v;
          e += 0.5 * mech.masses[f].mass * v.squaredNorm();
        }
        result.monitors.max_leg_vibration_energy =
            std::max(result.monitors.max_leg_vibration_energy, e);
      }
      if (!run.stance && model.spring_legs && prs.hip_rotation) place_legs(t, y);
    } else if (event == kTouchdown) {
      finish_stride(t);
      ++touchdown_events;
      if (touchdowns >= sim.max_strides) break;
      const control::BodyState s = run.body_state(y);
      const control::StancePlan plan = control::plan_stance(context(t, false), touchdowns, t, s);
      current = reduced::StrideRecord{};
      have_stride = true;
      run.stride_slip = 0.0;
      current.index = touchdowns++;
      current.t_touchdown = t;
      current.position = s.position;
      current.velocity = s.velocity;
      current.euler123 = s.euler123;
      current.omega = s.omega;
      current.setpoint =
          scene.controller.setpoint_position + scene.controller.setpoint_velocity * t;
      current.P_requested = plan.command.P_world;
      current.H_requested = plan.command.H_body;
      current.gravity_compensation = plan.gravity_compensation;
      current.active_legs = plan.active_legs;
      current.allocation = plan.allocation_status;
      if (plan.allocation_status != control::AllocationStatus::kOk) {
        ++res.warnings[plan.allocation_status == control::AllocationStatus::kLimited
                           ? "allocation_limited"
                           : "allocation_infeasible"];
      }
      p_touchdown = total_momentum(y);
      // Leg controllers: a constant force along each leg for the stance duration T;
      // with a force limit the pulse saturates, and with impulse feedback the actuator
      // stays on until its delivered impulse reaches the allocation (seed 5.4).
      const double T = prs.actuators ? plan.duration : 0.0;
      double stance_end = t;
      Vector3d H = Vector3d::Zero();
      double peak = 0.0;
      std::fill(leg_force.begin(), leg_force.end(), 0.0);
      std::fill(armed_force.begin(), armed_force.end(), 0.0);
      for (size_t i = 0; i < legs && T > 0.0 && i < plan.leg_impulse.size(); ++i) {
        const Vector3d p = plan.leg_impulse[i];
        double impulse = 0.0;  // signed along the push direction [N s]
        if (model.spring_legs) {
          impulse = p.dot(run.push[i]);
        } else if (p.norm() > 0.0) {
          run.push[i] = p.normalized();
          impulse = p.norm();
        }
        if (impulse == 0.0) continue;
        double f = impulse / T, duration = T;
        if (prs.actuator_max_force > 0.0 && std::abs(f) > prs.actuator_max_force) {
          f = std::copysign(prs.actuator_max_force, f);
          if (prs.impulse_feedback) {
            // The leg measures the net impulse it gives the body (its force minus its
            // share s of the weight it was compensating for, shares in proportion to
            // the legs' impulses) and stays on until that reaches its allocation net of
            // compensation: F_max T' - s T' = p - s T.
            double sum = 0.0;
            for (const auto& q : plan.leg_impulse) sum += q.norm();
            const double share =
                sum > 0.0 ? plan.gravity_compensation / T * std::abs(impulse) / sum : 0.0;
            const double net_rate = prs.actuator_max_force - share;
            duration = net_rate > 0.0 ? (std::abs(impulse) - share * T) / net_rate
                                      : std::abs(impulse) / prs.actuator_max_force;
          }
          ++res.warnings["actuator_saturated"];
        }
        leg_force[i] = f;
        off_time[i] = t + duration;
        armed_force[i] = f;
        armed_duration[i] = duration;
        stance_end = std::max(stance_end, off_time[i]);
        peak = std::max(peak, std::abs(f));
        H += model.hip[i].cross(f * duration * run.push[i]);
      }
      stride_force = leg_force;
      current.stance_duration = stance_end - t;
      current.peak_leg_force = peak;
      current.H_delivered = H;
      run.stance = stance_end > t;
      if (run.stance && model.spring_legs) {
        armed = true;  // fire at the bottom of the stance
        std::fill(leg_force.begin(), leg_force.end(), 0.0);
      }
      sys.set_actuators(leg_force, run.push);
    } else if (event == kBottom) {
      armed = false;
      double stance_end = t;
      for (size_t i = 0; i < legs; ++i) {
        leg_force[i] = armed_force[i];
        off_time[i] = t + armed_duration[i];
        if (leg_force[i] != 0.0) stance_end = std::max(stance_end, off_time[i]);
      }
      if (have_stride) current.stance_duration = stance_end - current.t_touchdown;
      sys.set_actuators(leg_force, run.push);
    } else if (event >= kFoot) {
      // A foot lands (its hip is freed in pitch) or lifts off (its slide takes the leg along
      // the leg's current direction; the foot's velocity across the line is the
      // hip's to catch). Energy changes are booked as hip work. Feet that crossed
      // together (a symmetric landing) switch together: an event fires only once.
      const size_t first = static_cast<size_t>(event - kFoot);
      const double e_before = msys.energies(y).total();
      bool any_free = false;
      for (size_t k = 0; k < legs; ++k) any_free = any_free || sys.free(k);
      const bool was_free = any_free;
      for (size_t i = 0; i < legs; ++i) {
        const int foot = model.foot[i];
        const double z = y[6 * foot + 2];
        const bool land = i == first ? !sys.free(i) : !sys.free(i) && z <= 0.0;
        const bool lift = i == first ? sys.free(i) : sys.free(i) && z >= kFootLift;
        pr::Surface& slide = mech.surfaces[model.slide[i]];
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
            slide.nodes.clear();
          }
          sys.set_free(i, true);
        } else if (lift) {
          const pr::BodyFrame f = msys.frames(y)[model.body];
          const Vector3d w = msys.body_omega(model.body, y);
          const pr::NodeRef ghost{pr::NodeRef::Kind::kGhost, slide.ghost};
          const Vector3d xf = y.segment<3>(6 * foot);
          const Vector3d arm = xf - msys.node_position(ghost, y);
          if (arm.norm() > 1e-9) {
            const Vector3d d = arm.normalized();
            const Vector3d vb = f.com_velocity + w.cross(xf - f.com);
            const Vector3d vrel = y.segment<3>(6 * foot + 3) / mech.masses[foot].mass - vb;
            y.segment<3>(6 * foot + 3) = mech.masses[foot].mass * (vb + vrel.dot(d) * d);
            slide.direction = f.rotation.transpose() * d;
            run.push[i] = -slide.direction;
          }
          slide.type = pr::SurfaceType::kLine;
          slide.bilateral = false;
          slide.nodes = model.mechanism.surfaces[model.slide[i]].nodes;
          sys.set_free(i, false);
        }
      }
      any_free = false;
      for (size_t k = 0; k < legs; ++k) any_free = any_free || sys.free(k);
      if (any_free && !was_free) run.contact_begin = t;
      if (!any_free && was_free) spring_stance = t - run.contact_begin;
      sys.set_actuators(leg_force, run.push);
      book_hip_work(result.monitors, msys.energies(y).total() - e_before);
    } else {
      // Reached t_target: an actuator switching off, a disturbance, or the end.
      if (run.stance && !armed) {
        bool on = false;
        for (size_t i = 0; i < legs; ++i) {
          if (leg_force[i] != 0.0 && off_time[i] <= t * (1.0 + 1e-14) + 1e-14) leg_force[i] = 0.0;
          on = on || leg_force[i] != 0.0;
        }
        sys.set_actuators(leg_force, run.push);
        run.stance = on;
      }
      while (next_disturbance < scene.disturbances.size() &&
             scene.disturbances[next_disturbance].time <= t) {
        const auto& d = scene.disturbances[next_disturbance++];
        // Linear impulse shared by the four body masses; angular impulse as the
        // rigid velocity change dw = I^-1 H (body frame).
        const pr::BodyFrame f = msys.frames(y)[model.body];
        const Vector3d dw = f.rotation * (scene.body.inertia.inverse() * d.angular_impulse);
        const auto& b = mech.bodies[model.body];
        const double e_before = msys.energies(y).total();
        const int rot = sys.rotation_state();
        if (rot >= 0) {  // rigid body: dp on its CoM mass, dL = R H
          y.segment<3>(6 * b.first_mass + 3) += d.linear_impulse;
          y.segment<3>(rot + 4) += f.rotation * d.angular_impulse;
        }
        for (int k = 0; k < (rot >= 0 ? 0 : 4); ++k) {
          const int j = b.first_mass + k;
          const Vector3d arm = y.segment<3>(6 * j) - f.com;
          y.segment<3>(6 * j + 3) += 0.25 * d.linear_impulse + mech.masses[j].mass * dw.cross(arm);
        }
        book_hip_work(result.monitors, msys.energies(y).total() - e_before);  // external work
      }
      if (t >= sim.duration) running = false;
    }
    if (running) {
      observer.restart();
      stepper->reset(sys, t, y);
    }
  }
  if (have_stride && !current.has_apex) {
    current.P_delivered = total_momentum(y) - p_touchdown +
                          Vector3d(0, 0, total_mass * g * (t - current.t_touchdown));
  }
  finish_stride(-1.0);
  result.monitors.actuator_work = run.work + result.monitors.hip_work;
  result.monitors.positive_actuator_work = run.positive_work + result.monitors.positive_hip_work;

  res.t_end = t;
  const control::BodyState s = run.body_state(y);
  res.final_position = s.position;
  res.final_velocity = s.velocity;
  res.final_euler123 = s.euler123;
  res.final_omega = s.omega;
  res.final_attitude = s.attitude;
  if (res.status == reduced::RunStatus::kCompleted) {
    res.reason = touchdowns >= sim.max_strides && t < sim.duration
                     ? "reached " + std::to_string(sim.max_strides) + " strides"
                     : "reached t = " + fmt(t) + " s";
  }
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
  result.monitors.zero_length_triggers = msys.zero_length_triggers();
  res.cost.solver = stepper->counters();
  res.cost.touchdowns = touchdown_events;
  res.cost.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace pronk::robot
