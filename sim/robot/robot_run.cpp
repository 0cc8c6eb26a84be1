// RobotRun's events and records: construction, the dispatch at a segment's end, the energy
// balance check, apex (hop-height feedback), touchdown (the stride's plan and integral
// actions), actuators switching off, disturbances, and the run's end.

#include "sim/robot/robot_run.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sim/pseudorigid/stability.hpp"
#include "sim/robot/feet_step_bound.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

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

RobotRun::RobotRun(const scene::Scene& scene, const RobotModel& model,
                   const RobotRunOptions& options)
    : scene_(scene),
      belief_(scene::controller_view(scene)),
      model_(model),
      prs_(scene.pseudo_rigid),
      legs_(model.hip.size()),
      g_(scene.gravity),
      l_(scene.legs.length),
      data_(model, belief_),
      sys_(model, data_.inputs, prs_),
      msys_(sys_.mechanism()),
      control_(belief_, model, data_),
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
  if (free_stance_ || model.quasi_static_feet) {
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
  balance0_ = sys_.energies(sys_.initial_state()).total();
  blowup_ = mech.simulation.energy_blowup_factor * mon.energy_scale;
  run_.balance0 = balance0_;
  run_.blowup = blowup_;
  solver_ = solver_options(prs_, mon.energy_scale);
  verlet_limit_ =
      solver_.method == ode::Method::kVerlet ? 2.0 / pr::max_frequency_bound(mech) : 0.0;
  if (model.quasi_static_feet && solver_.method == ode::Method::kVerlet) {
    verlet_limit_ = 2.0 / quasi_static_omega(scene, model);  // the body on its landed feet
  }
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
    default:
      break;
  }
  run::Next next = run::Next::kContinue;
  switch (event) {
    case kApex:
      on_apex(t, y);
      break;
    case kTouchdown:
      next = on_touchdown(t, y);
      break;
    case kBottom:
      on_bottom(t, y);
      break;
    case -1:
      next = on_time(t, y);
      break;
    default:
      on_foot(static_cast<size_t>(event - kFoot), t, y);
      break;
  }
  // (A foot event switched every foot due with it: on_foot.)
  if (sys_.quasi_static() && event < kFoot) catch_up_feet(t, y);
  return next;
}

double RobotRun::fixed_step(double, const ode::Vec&) const {
  if (!sys_.quasi_static() || solver_.method != ode::Method::kVerlet || !(solver_.h_flight > 0.0))
    return 0.0;
  for (size_t i = 0; i < legs_; ++i) {
    if (sys_.pinned(i) || sys_.free(i))
      return solver_.h_fixed;  // a foot on (or just off) the ground
  }
  return solver_.h_flight;
}

/// Quasi-static feet whose switch fell on this event's instant without a crossing of their
/// own (a level drop: every foot reaches the ground as the CoM crosses the leg length): a foot
/// in the air at or below the ground lands, a landed foot the ground no longer presses lifts.
void RobotRun::catch_up_feet(double t, ode::Vec& y) {
  for (size_t i = 0; i < legs_; ++i) {
    if (quasi_static_due(i, y)) {
      on_foot(i, t, y);
      return;  // (on_foot switches every foot due with it)
    }
  }
}

/// The energy balance at a segment's end (or at a sample on the way that blew up first):
/// false ends the run as diverged.
bool RobotRun::energy_ok(double t, const ode::Vec& y, const ode::Stepper& stepper) {
  const double balance =
      sys_.energies(y).total() + run_.dissipated - run_.work - result.monitors.hip_work;
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
    if (data_.has_placed && prs_.placement_trim_gain > 0.0) {
      // What the placed legs missed, asked for on top at the next placements.
      const double cap = total_mass_ * std::sqrt(2.0 * g_ * h);
      Eigen::Vector2d& b = data_.placement_trim;
      // Along the setpoint velocity only: the stance's travel is what the placement models
      // worst; across it the lateral loop's own placement holds.
      const Eigen::Vector2d v_d = scene_.controller.setpoint_velocity.head<2>();
      if (v_d.norm() > 1e-9) {
        const Eigen::Vector2d u = v_d.normalized();
        b += prs_.placement_trim_gain * data_.placed_response *
             u.dot(data_.placed - current_.P_delivered.head<2>()) * u;
      }
      if (b.norm() > cap) b *= cap / b.norm();
    }
    data_.has_placed = false;
  }
  if (!run_.stance && model_.spring_legs) {
    // Foot vibration on the leg springs (free fall: the springs would be at rest).
    const Com c = body_com(model_, y);
    double e = sys_.energies(y).leg;
    for (int f : model_.foot) {
      if (f < 0) continue;  // (quasi-static feet: their legs' energy is all)
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
  const control::BodyState s = run_.body_state(y);  // the stride's record: the true state
  const control::BodyState read = sensed(s);
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
          std::clamp(data_.attitude_trim[k] + prs_.attitude_trim_gain * read.euler123[k],
                     -prs_.attitude_trim_max, prs_.attitude_trim_max);
    }
  }
  const control::StancePlan plan =
      control::plan_stance(control_.context(t, false), touchdowns_, t, trimmed(read));
  current_ = reduced::open_stride(touchdowns_++, t, s, plan, scene_, result.run.warnings);
  // The stance attitude feedback holds the tilt that the integral action has learnt, as its
  // sensor reads it (a bias b read on top of the tilt holds the body at -b).
  sys_.set_stance_tilt(-data_.attitude_trim - prs_.attitude_sensor_bias);
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
  const double e_before = sys_.energies(y).total();
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
  if (!result.monitors.energy_measured) result.monitors.energy_drift = 0.0;
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

}  // namespace pronk::robot::detail
