// RobotSystem's quasi-static (massless) feet (RobotModel::quasi_static_feet).
//
// A massless foot transmits what holds it in balance. In the air nothing holds it: it sits on
// its leg's line at the rest length minus the leg's shortening q, which relaxes as a foot
// between the leg spring, its damper and the actuator does (k q - c dl/dt + a = 0, so
// dq/dt = -(k q + a) / c, towards the rest length plus a / k), and the body feels nothing of
// the leg (the actuator acts on nothing). Its velocity is continuous at lift-off (the ground
// force is zero there), so a lifted foot does not sink into the ground. On the ground the
// foot is pinned at its ground position s (two integrated states); the leg's spring (the foot
// pressed into the ground spring in series: the depth that balances them, one Newton step from the
// surface) pushes the hip along the foot -> hip line, the slot (stiffness internal_stiffness;
// for a free hip a bilateral plane through the hip holding the leg and the body x axis, for a
// locked hip the leg's line, two such planes: slot_normals) pushes the body at the foot across
// it, and the ground takes their sum plus the leg's damper and actuator. Its tangential part
// F_t is held by friction: the regularised Coulomb law F_t = -mu N v / sqrt(|v|^2 + v_s^2)
// read backwards is the foot's creep, v = v_s r / sqrt(1 - r^2) along the push, r = |F_t| /
// (mu N); on frictionless ground (mu = 0, a locked hip's line holding the foot) the foot
// slides to where the springs balance. Method verlet advances s in MechanicalSystem::relax at the
// step's start, by backward Euler as the minimum of the springs' energy plus the friction's
// dissipation potential mu N (sqrt(|v|^2 + v_s^2) - v_s) h over the step, so both kicks read the
// forces after the slide; the energy the slide releases is booked as dissipated. The leg dampers
// act in the dissipation split on the body (the foot held), the actuators in extra_forces.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "sim/pseudorigid/attitude.hpp"
#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/robot/feet_step_bound.hpp"
#include "sim/robot/robot_system.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;
using Eigen::Matrix2d;
using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {
constexpr double kMaxSlide = 0.02;  ///< largest slide of a foot in one relaxation [m]
constexpr int kMaxIterations = 30;  ///< Newton iterations of one foot's creep
}  // namespace

ode::Vec RobotSystem::initial_state() const {
  const ode::Vec y0 = model_.mechanism.initial_state();
  if (qs_states_ == 0) return y0;
  ode::Vec y = ode::Vec::Zero(dimension());
  y.head(y0.size()) = y0;
  return y;
}

RobotSystem::Slot RobotSystem::to_world(const std::array<Vector3d, 2>& body, const Matrix3d& R) {
  Slot sl;
  for (const Vector3d& n : body) {
    if (n.squaredNorm() > 0.0) sl.n[static_cast<size_t>(sl.count++)] = R * n;
  }
  return sl;
}

RobotSystem::Slot RobotSystem::slot_world(size_t i, const ode::Vec& y) const {
  return to_world(slot_[i], sys_.frames(y)[model_.body].rotation);
}

Vector3d RobotSystem::foot_position(size_t i, const ode::Vec& y) const {
  if (model_.foot[i] >= 0) return y.segment<3>(6 * model_.foot[i]);
  const Vector3d hip = sys_.node_position(model_.hip_node[i], y);
  if (pinned_[i]) return stance_at(i, y).foot;
  const Matrix3d& R = sys_.frames(y)[model_.body].rotation;
  return hip + (rest_[i] - y[foot_state(i)]) * (R * dir_[i]);
}

RobotSystem::Stance RobotSystem::stance(size_t i, const Vector2d& s, const Vector3d& hip,
                                        const Slot& sl) const {
  Stance st;
  double slot_energy = 0.0;  // 2 x the slot springs' energy [J]
  auto at = [&](double z) {
    st.foot = Vector3d(s.x(), s.y(), z);
    const Vector3d L = hip - st.foot;
    st.l = L.norm();
    st.d = st.l > 1e-12 ? Vector3d(L / st.l) : Vector3d::UnitZ();
    st.spring = k_leg_ * (rest_[i] - st.l);
    st.slot.setZero();
    slot_energy = 0.0;
    for (int j = 0; j < sl.count; ++j) {
      const double e = (st.foot - hip).dot(sl.n[static_cast<size_t>(j)]);
      st.slot += k_slot_ * e * sl.n[static_cast<size_t>(j)];
      slot_energy += k_slot_ * e * e;
    }
  };
  at(0.0);
  // The ground spring in series: the depth at which it carries what the leg and the slot
  // press into it (linearised about the surface).
  const double pressed = st.spring * st.d.z() + st.slot.z();
  if (pressed > 0.0 && k_ground_ > 0.0) {
    double k_slot_z = 0.0;  // the slot springs' vertical stiffness
    for (int j = 0; j < sl.count; ++j) {
      const double nz = sl.n[static_cast<size_t>(j)].z();
      k_slot_z += k_slot_ * nz * nz;
    }
    st.depth = pressed / (k_ground_ + k_leg_ * st.d.z() * st.d.z() + k_slot_z);
    at(-st.depth);
  }
  const double x = rest_[i] - st.l;
  st.energy = 0.5 * (k_leg_ * x * x + slot_energy + k_ground_ * st.depth * st.depth);
  return st;
}

bool RobotSystem::same_key(const ode::Vec& y, Eigen::VectorXd& key, bool store) const {
  const int nb = body_key_size();
  if (store) {
    key.resize(nb + qs_states_);
    if (rotation_ >= 0) {
      key.head<3>() = y.segment<3>(body_first_);
      key.segment<4>(3) = y.segment<4>(rotation_);
    } else {
      for (int j = 0; 3 * j < nb; ++j) key.segment<3>(3 * j) = y.segment<3>(6 * j);
    }
    key.tail(qs_states_) = y.segment(mech_dim_, qs_states_);
    return true;
  }
  if (key.size() != nb + qs_states_) return false;
  if (!(key.tail(qs_states_).array() == y.segment(mech_dim_, qs_states_).array()).all())
    return false;
  if (rotation_ >= 0) {
    return (key.head<3>().array() == y.segment<3>(body_first_).array()).all() &&
           (key.segment<4>(3).array() == y.segment<4>(rotation_).array()).all();
  }
  for (int j = 0; 3 * j < nb; ++j) {
    if (!(key.segment<3>(3 * j).array() == y.segment<3>(6 * j).array()).all()) return false;
  }
  return true;
}

const RobotSystem::Stance& RobotSystem::stance_at(size_t i, const ode::Vec& y) const {
  // Keyed on what a stance reads of y: the body's positions (and attitude) and the feet's
  // states.
  if (!(st_memo_ && same_key(y, st_key_, false))) {
    same_key(y, st_key_, true);
    st_.resize(pinned_.size());
    for (size_t k = 0; k < pinned_.size(); ++k) {
      if (!pinned_[k]) continue;
      st_[k] = stance(k, y.segment<2>(foot_state(k)), sys_.node_position(model_.hip_node[k], y),
                      slot_world(k, y));
    }
    st_memo_ = true;
  }
  return st_[i];
}

double RobotSystem::applied_actuator(size_t i) const {
  double f = settings_.actuator_gain * (force_[i] + fb_[i]);
  if (settings_.actuator_max_force > 0.0) {
    f = std::clamp(f, -settings_.actuator_max_force, settings_.actuator_max_force);
  }
  return f;
}

Vector3d RobotSystem::reaction(const Stance& st, const Vector3d& vh, double a) const {
  const double T = st.spring - c_leg_ * st.d.dot(vh) + a;
  return T * st.d + st.slot;
}

void RobotSystem::add_feet(const ode::Vec& y, bool damped, bool rates, ode::Vec& dydt) const {
  if (rates) feedback(y);
  Vector3d tau = Vector3d::Zero();
  bool loaded = false;
  for (size_t i = 0; i < pinned_.size(); ++i) {
    const int k = foot_state(i);
    dydt[k] = dydt[k + 1] = 0.0;
    if (!pinned_[i]) {  // in the air: the leg's shortening relaxes
      if (rates && c_leg_ > 0.0) dydt[k] = -(k_leg_ * y[k] + applied_actuator(i)) / c_leg_;
      continue;
    }
    const Vector3d hip = sys_.node_position(model_.hip_node[i], y);
    const Stance& st = stance_at(i, y);
    Vector3d vh = Vector3d::Zero();
    if (damped || rates) vh = sys_.node_velocity(model_.hip_node[i], y);
    const double T = st.spring - (damped ? c_leg_ * st.d.dot(vh) : 0.0);
    const Vector3d& f_slot = st.slot;
    // The slot's force acts at the foot: at the hip, and the moment of its turning normal.
    load_hip(i, T * st.d + f_slot, y, dydt);
    tau += (st.foot - hip).cross(f_slot);
    loaded = true;
    if (!rates) continue;
    const Vector3d g = reaction(st, vh, applied_actuator(i));
    const double grip = std::max(mu_, 1e-3) * g.z();
    if (!(grip > 0.0)) continue;
    const Vector2d push = -g.head<2>();
    const double r = std::min(push.norm() / grip, 1.0 - 1e-9);
    dydt.segment<2>(k) = v_slip_ * push / (grip * std::sqrt(1.0 - r * r));
  }
  if (loaded) load_torque(tau, y, dydt);
}

void RobotSystem::load_hip(size_t i, const Vector3d& f, const ode::Vec& y, ode::Vec& dydt) const {
  const pr::Body& body = model_.mechanism.bodies[model_.body];
  const pr::NodeRef& h = model_.hip_node[i];
  if (rotation_ >= 0) {
    dydt.segment<3>(6 * body.first_mass + 3) += f;
    dydt.segment<3>(rotation_ + 4) +=
        (sys_.node_position(h, y) - sys_.frames(y)[model_.body].com).cross(f);
  } else if (h.kind == pr::NodeRef::Kind::kMass) {
    dydt.segment<3>(6 * h.index + 3) += f;
  } else {
    const auto& g = model_.mechanism.ghost_points[h.index];
    for (int j = 0; j < 4; ++j) dydt.segment<3>(6 * (body.first_mass + j) + 3) += g.weights[j] * f;
  }
}

void RobotSystem::load_torque(const Vector3d& tau, const ode::Vec& y, ode::Vec& dydt) const {
  if (rotation_ >= 0) {
    dydt.segment<3>(rotation_ + 4) += tau;
    return;
  }
  const pr::Body& body = model_.mechanism.bodies[model_.body];
  const pr::BodyFrame& fr = sys_.frames(y)[model_.body];
  const std::array<Matrix3d, 4> omega = pr::attitude_derivative(fr, body.local);
  const Vector3d tau_body = fr.rotation.transpose() * tau;
  for (int j = 0; j < 4; ++j) {
    dydt.segment<3>(6 * (body.first_mass + j) + 3) += omega[j].transpose() * tau_body;
  }
}

double RobotSystem::booked_body(const ode::Vec& y_ref, const ode::Vec& y0,
                                const ode::Vec& y) const {
  const pr::Body& body = model_.mechanism.bodies[model_.body];
  double booked = 0.0;
  for (size_t k = 0; k < inv_mass_.size(); ++k) {
    const int at = 6 * static_cast<int>(k) + 3;
    const Vector3d dp = y.segment<3>(at) - y0.segment<3>(at);
    booked -= dp.dot(y_ref.segment<3>(at) + 0.5 * dp) * inv_mass_[k];
  }
  if (rotation_ >= 0) {
    const Matrix3d iw = pr::rigid_inverse_inertia(body, sys_.frames(y)[model_.body].rotation);
    const Vector3d dL = y.segment<3>(rotation_ + 4) - y0.segment<3>(rotation_ + 4);
    booked -= dL.dot(iw * (y_ref.segment<3>(rotation_ + 4) + 0.5 * dL));
  }
  return booked;
}

Vector2d RobotSystem::creep(size_t i, double h, const Vector2d& s0, const Vector3d& hip,
                            const Slot& sl, const Vector3d& vh, double a, double* released) const {
  const Stance st0 = stance(i, s0, hip, sl);
  *released = 0.0;
  const double normal = reaction(st0, vh, a).z();
  if (!(normal > 0.0)) return s0;  // lifting off: the event takes it
  const double grip = mu_ * normal;
  const double hv = h * v_slip_;
  // Phi(D) = W(s0 + D) + grip (sqrt(|D|^2 + (h v_s)^2) - h v_s), W the springs' energy with
  // the damper and actuator as constant forces along the leg (grad W = the ground's
  // tangential reaction g_t).
  struct Point {
    Vector2d D, grad;
    double phi;
    Stance st;
  };
  auto point = [&](const Vector2d& D, const Stance& st) {
    Point q;
    q.D = D;
    q.st = st;
    const double axial = a - c_leg_ * q.st.d.dot(vh);
    const double rho = std::sqrt(D.squaredNorm() + hv * hv);
    q.phi = q.st.energy - axial * q.st.l + grip * (rho - hv);
    q.grad = reaction(q.st, vh, a).head<2>() + grip * D / rho;
    return q;
  };
  auto eval = [&](const Vector2d& D) { return point(D, stance(i, s0 + D, hip, sl)); };
  // The slot's stiffness across the ground (its normals' ground parts).
  Matrix2d K_slot = Matrix2d::Zero();
  for (int j = 0; j < sl.count; ++j) {
    const Vector2d nt = sl.n[static_cast<size_t>(j)].head<2>();
    K_slot += k_slot_ * nt * nt.transpose();
  }
  Point q = point(Vector2d::Zero(), st0);
  for (int it = 0; it < kMaxIterations; ++it) {
    const double rho = std::sqrt(q.D.squaredNorm() + hv * hv);
    const Vector2d dt = q.st.d.head<2>();
    Matrix2d H = k_leg_ * dt * dt.transpose() + K_slot;
    H += (grip / rho) * (Matrix2d::Identity() - q.D * q.D.transpose() / (rho * rho));
    H += 1e-9 * (k_leg_ + k_slot_ + grip / hv) * Matrix2d::Identity();
    Vector2d step = -H.ldlt().solve(q.grad);
    if (!step.allFinite()) break;
    // (converged: a step below the resolution of the ground position)
    if (step.norm() <= 1e-13 + 1e-10 * q.D.norm()) break;
    if (step.norm() > kMaxSlide) step *= kMaxSlide / step.norm();
    double t = 1.0;
    Point next = eval(q.D + step);
    while (!(next.phi <= q.phi + 1e-4 * t * q.grad.dot(step)) && t > 1e-6) {
      t *= 0.5;
      next = eval(q.D + t * step);
    }
    if (!(next.phi <= q.phi)) break;  // no descent left (round-off): q is the minimum
    q = next;
    if (q.D.norm() >= kMaxSlide) break;
  }
  *released = st0.energy - q.st.energy;
  return s0 + q.D;
}

double RobotSystem::relax(double h, ode::Vec& y, bool* forces_moved) const {
  double released = 0.0;
  *forces_moved = false;  // (a foot in the air pushes nothing)
  feedback(y);
  for (size_t i = 0; i < pinned_.size(); ++i) {
    const int k = foot_state(i);
    if (!pinned_[i]) {  // in the air: the shortening relaxes exactly, to -a / k
      const double q0 = y[k], q_end = -applied_actuator(i) / k_leg_;
      y[k] = c_leg_ > 0.0 ? q_end + (q0 - q_end) * std::exp(-h * k_leg_ / c_leg_) : q_end;
      continue;
    }
    const Vector3d hip = sys_.node_position(model_.hip_node[i], y);
    const Vector3d vh = sys_.node_velocity(model_.hip_node[i], y);
    const Vector2d s0 = y.segment<2>(k);
    double lost = 0.0;
    const Vector2d s1 = creep(i, h, s0, hip, slot_world(i, y), vh, applied_actuator(i), &lost);
    released += lost;
    y.segment<2>(k) = s1;
    *forces_moved = *forces_moved || s1 != s0;
  }
  return released;
}

double RobotSystem::dissipate(double t, double h, const ode::Vec& y_ref, ode::Vec& y) const {
  const double inner = sys_.dissipate(t, h, y_ref, y);
  if (qs_states_ == 0 || !(c_leg_ > 0.0)) return inner;
  bool any = false;
  // Each landed leg's damper between the hip and the held foot, backward Euler at fixed
  // positions: the extension rate u falls to u / (1 + w c h), w the hip's inverse effective
  // mass along the leg.
  for (size_t i = 0; i < pinned_.size(); ++i) {
    if (!pinned_[i]) continue;
    if (!any) y_damp_ = y;
    any = true;
    const Stance st = stance_at(i, y);
    const pr::NodeRef& hip = model_.hip_node[i];
    const double w = sys_.inverse_mass_along(hip, y, st.d);
    const double u = st.d.dot(sys_.node_velocity(hip, y));
    sys_.add_impulse(hip, (-c_leg_ * h * u / (1.0 + w * c_leg_ * h)) * st.d, y);
  }
  if (!any) return inner;
  return inner + booked_body(y_ref, y_damp_, y);
}

pr::Energies RobotSystem::energies(const ode::Vec& y) const {
  pr::Energies e = sys_.energies(y);
  for (int i = 0; i < qs_states_ / 2; ++i) e.leg += foot_energy(static_cast<size_t>(i), y);
  return e;
}

double RobotSystem::foot_energy(size_t i, const ode::Vec& y) const {
  // A massless foot in the air holds its leg's spring against its damper and actuator,
  // apart from the body: its energy is the leg's own (RobotRun books what a foot takes
  // away at lift-off as dissipated, and what it brings at landing as actuator work).
  if (!pinned_[i]) return 0.0;
  return stance_at(i, y).energy;
}

Vector3d RobotSystem::ground_reaction(size_t i, const ode::Vec& y, bool fb) const {
  if (!pinned_[i]) return Vector3d::Zero();
  if (fb) feedback(y);
  const Stance& st = stance_at(i, y);
  return reaction(st, sys_.node_velocity(model_.hip_node[i], y), applied_actuator(i));
}

double RobotSystem::foot_event(size_t i, const ode::Vec& y) const {
  if (pinned_[i]) return ground_reaction(i, y).z();
  const Vector3d f = foot_position(i, y);
  if (f.z() > 0.0) return f.z();
  // At or below the ground in the air: it lands once the ground would press it (the leg
  // shortens faster than its spring and damper extend it) by land_force_: a foot that lifted
  // at zero force does not land again at once (the zero-force boundary is both states'; with
  // no band between them a foot resting unloaded switches at every step).
  feedback(y);
  const Vector3d hip = sys_.node_position(model_.hip_node[i], y);
  const Slot sl = to_world(slot_normals(dir_[i], locked_), sys_.frames(y)[model_.body].rotation);
  const Stance st = stance(i, f.head<2>(), hip, sl);
  const double pressed =
      reaction(st, sys_.node_velocity(model_.hip_node[i], y), applied_actuator(i)).z();
  return land_force_ - pressed;
}

void RobotSystem::land_foot(size_t i, ode::Vec& y) {
  const Vector3d f = foot_position(i, y);
  y.segment<2>(foot_state(i)) = f.head<2>();
  slot_[i] = slot_normals(dir_[i], locked_);
  pinned_[i] = true;
  free_[i] = !locked_;  // a free hip turns in its slot; a locked one keeps the leg's line
  drop_memos();
}

void RobotSystem::lift_foot(size_t i, ode::Vec& y) {
  // (on the surface: the ground spring lets go as the foot leaves it)
  const Vector3d hip = sys_.node_position(model_.hip_node[i], y);
  const Vector2d s = y.segment<2>(foot_state(i));
  const Vector3d L = Vector3d(s.x(), s.y(), 0.0) - hip;
  const double l = L.norm();
  if (l > 1e-9 && !locked_) dir_[i] = sys_.frames(y)[model_.body].rotation.transpose() * (L / l);
  y[foot_state(i)] = rest_[i] - l;
  y[foot_state(i) + 1] = 0.0;
  pinned_[i] = false;  // (its hip stays free until the foot has risen: RobotRun)
  drop_memos();
}

}  // namespace pronk::robot
