// MechanismSystem's skeleton: construction, the state's kinematics (node positions and
// velocities, body frames, rigid bodies' rotation memos), the right-hand side (evaluate) and
// the mechanical interface of method verlet (momenta, drift, kinetic energy).
#include "sim/pseudorigid/system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/pseudorigid/system_detail.hpp"

namespace pronk::pseudorigid {

MechanismSystem::MechanismSystem(const Mechanism& m)
    : MechanismSystem(m, std::make_unique<const MechanismInputs>(m), nullptr) {}

MechanismSystem::MechanismSystem(const Mechanism& m, const MechanismInputs& inputs)
    : MechanismSystem(m, nullptr, &inputs) {}

MechanismSystem::MechanismSystem(const Mechanism& m, std::unique_ptr<const MechanismInputs> own,
                                 const MechanismInputs* inputs)
    : m_(m),
      own_inputs_(std::move(own)),
      in_(inputs != nullptr ? inputs : own_inputs_.get()),
      fit_x_(m.bodies.size()),
      fit_frame_(m.bodies.size()),
      fit_valid_(m.bodies.size(), false),
      rigid_(m.bodies.size()),
      frames_(m.bodies.size()),
      dframes_(m.bodies.size()),
      force_(ode::Vec::Zero(3 * static_cast<int>(m.masses.size()))),
      torque_(m.bodies.size(), Vector3d::Zero()) {
  if (in_->rest_length.size() != m.connections.size() ||
      in_->surfaces.size() != m.surfaces.size()) {
    throw std::invalid_argument("MechanismSystem: inputs not sized to the mechanism");
  }
  for (const Mass& ms : m.masses) inv_mass_.push_back(1.0 / ms.mass);
  for (int b = 0; b < static_cast<int>(m.bodies.size()); ++b) {
    rot_.push_back(m.rotation_state(b));
    any_rigid_ = any_rigid_ || rot_.back() >= 0;
  }
  bool attached = false;
  for (const Surface& s : m.surfaces) attached = attached || s.body >= 0;
  has_attached_surfaces_ = attached;
  for (const Connection& c : m.connections) {
    has_power_flows_ = has_power_flows_ || c.damping > 0.0 || c.friction > 0.0 || c.drag > 0.0;
    has_actuator_work_ = has_actuator_work_ || c.kind == ConnectionClass::kActuator;
  }
  for (const Surface& s : m.surfaces) {
    has_power_flows_ = has_power_flows_ || s.damping > 0.0 || s.friction > 0.0;
  }
  has_actuator_work_ = has_actuator_work_ || !m.body_forces.empty() || !m.impulse_actuators.empty();
  has_power_flows_ = has_power_flows_ || has_actuator_work_;
  if (m.simulation.ghost_transfer == GhostTransfer::kMinNorm) {
    auto ghost = [](const NodeRef& n) { return n.kind == NodeRef::Kind::kGhost; };
    for (const Connection& c : m.connections) {
      const bool dissipative = c.kind != ConnectionClass::kActuator &&
                               (c.damping > 0.0 || c.friction > 0.0 || c.drag > 0.0);
      if (dissipative && (ghost(c.a) || ghost(c.b))) dissipation_split_ = false;
    }
    for (const Surface& s : m.surfaces) {
      if (s.body >= 0 || (s.damping == 0.0 && s.friction == 0.0)) continue;
      for (const NodeRef& n : s.nodes) {
        if (ghost(n)) dissipation_split_ = false;
      }
    }
  }
  rhs_needs_frames_ =
      any_rigid_ || attached || !m.body_forces.empty() || !m.impulse_actuators.empty() ||
      (m.simulation.ghost_transfer == GhostTransfer::kMinNorm && !m.ghost_points.empty());
}

const BodyFrame& MechanismSystem::fitted_frame(int b, const ode::Vec& y) const {
  const Body& body = m_.bodies[b];
  if (body.rigid) {
    BodyFrame& f = fit_frame_[b];
    f.com = seg(y, 6 * body.first_mass);
    f.rotation = rigid_pose(b, y).rotation;
    f.stretch.setIdentity();
    return f;
  }
  std::array<Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = seg(y, 6 * (body.first_mass + i));
  // Exact comparison: the same positions give the same fit, bit for bit.
  if (!fit_valid_[b] || x != fit_x_[b]) {
    fit_frame_[b] = fit_attitude(x, body.local);
    fit_x_[b] = x;
    fit_valid_[b] = true;
  }
  return fit_frame_[b];
}

void MechanismSystem::update_frames(const ode::Vec& y, bool derivatives) const {
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    frames_[b] = fitted_frame(static_cast<int>(b), y);
    if (derivatives && !m_.bodies[b].rigid) {
      dframes_[b] = attitude_derivative(frames_[b], m_.bodies[b].local);
    }
  }
}

const std::vector<BodyFrame>& MechanismSystem::frames(const ode::Vec& y) const {
  update_frames(y, false);
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    if (m_.bodies[b].rigid) {
      frames_[b].com_velocity = seg(y, 6 * m_.bodies[b].first_mass + 3) / m_.bodies[b].mass;
      continue;
    }
    Vector3d v = Vector3d::Zero();
    for (int i = 0; i < 4; ++i) v += 0.25 * seg(y, 6 * (m_.bodies[b].first_mass + i) + 3);
    frames_[b].com_velocity = v / (0.25 * m_.bodies[b].mass);  // equal masses m/4
  }
  return frames_;
}

Vector3d MechanismSystem::point_position(const NodeRef& n, const ode::Vec& y) const {
  if (n.kind == NodeRef::Kind::kAnchor) return m_.anchors[n.index].position;
  const GhostPoint& g = m_.ghost_points[n.index];  // of a four-mass body: barycentric
  const int f = m_.bodies[g.body].first_mass;
  Vector3d x = Vector3d::Zero();
  for (int i = 0; i < 4; ++i) x += g.weights[i] * seg(y, 6 * (f + i));
  return x;
}

Vector3d MechanismSystem::point_velocity(const NodeRef& n, const ode::Vec& y) const {
  if (n.kind == NodeRef::Kind::kAnchor) return Vector3d::Zero();
  const GhostPoint& g = m_.ghost_points[n.index];  // of a four-mass body: barycentric
  const int f = m_.bodies[g.body].first_mass;
  Vector3d v = Vector3d::Zero();
  for (int i = 0; i < 4; ++i) v += g.weights[i] * inv_mass_[f + i] * seg(y, 6 * (f + i) + 3);
  return v;
}

Vector3d MechanismSystem::reference_position(int i, const ode::Vec& y) const {
  const ReferencePoint& r = m_.reference_points[i];
  const BodyFrame& f = fitted_frame(r.body, y);
  return f.com + f.rotation * r.local;
}

Vector3d MechanismSystem::body_omega(int b, const ode::Vec& y) const {
  const Body& body = m_.bodies[b];
  if (body.rigid) return rigid_state(b, y).omega;
  std::array<Vector3d, 4> x, v;
  for (int k = 0; k < 4; ++k) {
    x[k] = seg(y, 6 * (body.first_mass + k));
    v[k] = seg(y, 6 * (body.first_mass + k) + 3) * inv_mass_[body.first_mass + k];
  }
  return fit_angular_velocity(x, v);
}

void MechanismSystem::rhs(double /*t*/, const ode::Vec& y, ode::Vec& dydt) const {
  evaluate(ForceSet::kAll, y, dydt);
}

void MechanismSystem::evaluate(ForceSet set, const ode::Vec& y, ode::Vec& dydt) const {
  // Body-attached surfaces need each body's attitude derivative: once per body here, not
  // once per constrained node.
  if (rhs_needs_frames_) update_frames(y, has_attached_surfaces_);
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) force_.segment<3>(3 * j) = m_.masses[j].mass * m_.gravity;
  if (any_rigid_) std::fill(torque_.begin(), torque_.end(), Vector3d::Zero());
  const bool memo = set == ForceSet::kConservative;  // (GeometryMemo)
  if (memo) begin_memo(y);
  add_connection_forces(set, y, memo);
  add_surface_forces(set, y, memo);
  for (const WorldForce& f : m_.world_forces) apply(f.node, f.force);
  for (const BodyForce& f : m_.body_forces) {
    if (active(f.t_start, f.t_end)) apply(f.node, frames_[f.body].rotation * f.force);
  }
  for (const ImpulseActuator& a : m_.impulse_actuators) {
    if (active(a.t_start, a.t_start + a.duration())) {
      apply(a.node, frames_[a.body].rotation * (a.force * a.direction));
    }
  }
  for (int j = 0; j < nm; ++j) {
    dydt.segment<3>(6 * j) = seg(y, 6 * j + 3) * inv_mass_[j];
    dydt.segment<3>(6 * j + 3) = force_.segment<3>(3 * j);
  }
  if (any_rigid_) rigid_rates(y, dydt);
  if (memo) memo_.valid = true;  // (another evaluation leaves it: it is keyed on its state)
}

void MechanismSystem::conservative_rhs(double /*t*/, const ode::Vec& y, ode::Vec& dydt) const {
  evaluate(ForceSet::kConservative, y, dydt);
}

void MechanismSystem::begin_memo(const ode::Vec& y) const {
  memo_.valid = false;
  memo_.y = y;
  memo_.surfaces = in_->surfaces;
  memo_.length.resize(m_.connections.size());
  memo_.pairs.clear();
}

bool MechanismSystem::memo_holds(const ode::Vec& y) const {
  if (!memo_.valid || memo_.y.size() != y.size()) return false;
  for (size_t j = 0; j < m_.masses.size(); ++j) {
    const int i = 6 * static_cast<int>(j);
    if (memo_.y.segment<3>(i) != y.segment<3>(i)) return false;
  }
  for (int r : rot_) {
    if (r >= 0 && memo_.y.segment<4>(r) != y.segment<4>(r)) return false;
  }
  return memo_.surfaces == in_->surfaces;
}

void MechanismSystem::rigid_rates(const ode::Vec& y, ode::Vec& dydt) const {
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    const int r = rot_[b];
    if (r < 0) continue;
    rigid_quaternion_rate(y, r, rigid_state(static_cast<int>(b), y).omega, dydt);
    dydt.segment<3>(r + 4) = torque_[b];
  }
}

// rigid_pose's miss: the rotation follows the quaternion alone (an impulse, a new angular
// momentum, keeps it).
const MechanismSystem::RigidState& MechanismSystem::update_rigid_pose(int b,
                                                                      const ode::Vec& y) const {
  RigidState& k = rigid_[static_cast<size_t>(b)];
  const int r = rot_[static_cast<size_t>(b)];
  k.key.head<4>() = y.segment<4>(r);
  k.key.tail<3>().setConstant(std::numeric_limits<double>::quiet_NaN());  // omega stale
  k.rotation = rigid_rotation(y, r);
  k.inverse_inertia = rigid_inverse_inertia(m_.bodies[static_cast<size_t>(b)], k.rotation);
  return k;
}

// rigid_state's miss: the angular velocity at the memo's rotation (rigid_pose current).
const MechanismSystem::RigidState& MechanismSystem::update_rigid_omega(int b,
                                                                       const ode::Vec& y) const {
  RigidState& k = rigid_[static_cast<size_t>(b)];
  const int r = rot_[static_cast<size_t>(b)];
  k.key.tail<3>() = y.segment<3>(r + 4);
  k.omega = rigid_omega(m_.bodies[static_cast<size_t>(b)], k.rotation, seg(y, r + 4));
  return k;
}

Matrix3d MechanismSystem::frame_inverse_inertia(size_t b) const {
  const RigidState& k = rigid_[b];
  const Matrix3d& rot = frames_[b].rotation;
  // The memo's when it was computed at this rotation (the same bits as computing it here;
  // a NaN key: never computed).
  if (!std::isnan(k.key[0]) && k.rotation == rot) return k.inverse_inertia;
  return rigid_inverse_inertia(m_.bodies[b], rot);
}

void MechanismSystem::momentum_mask(ode::Vec& mask) const {
  const int nm = static_cast<int>(m_.masses.size());
  mask.setZero(dimension());
  for (int j = 0; j < nm; ++j) mask.segment<3>(6 * j + 3).setOnes();
  for (int r : rot_) {
    if (r >= 0) mask.segment<3>(r + 4).setOnes();
  }
}

void MechanismSystem::position_rate(const ode::Vec& y, ode::Vec& dydt) const {
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) dydt.segment<3>(6 * j) = seg(y, 6 * j + 3) * inv_mass_[j];
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    const int r = rot_[b];
    if (r < 0) continue;
    rigid_quaternion_rate(y, r, rigid_state(static_cast<int>(b), y).omega, dydt);
  }
}

double MechanismSystem::kinetic_energy(const ode::Vec& y) const {
  const int nm = static_cast<int>(m_.masses.size());
  double k = 0.0;
  for (int j = 0; j < nm; ++j) k += 0.5 * seg(y, 6 * j + 3).squaredNorm() * inv_mass_[j];
  // A rigid body's rotation, in the attitude of the last frames (the metric is evaluated on
  // force vectors, whose position entries hold no attitude).
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    const int r = rot_[b];
    if (r < 0) continue;
    const Vector3d l = seg(y, r + 4);
    k += 0.5 * l.dot(frame_inverse_inertia(b) * l);
  }
  return k;
}

void MechanismSystem::drift(double h, ode::Vec& y) const {
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) y.segment<3>(6 * j) += h * (seg(y, 6 * j + 3) * inv_mass_[j]);
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    // (The rotation from the rigid_pose memo: the same expression, computed once per pose.)
    const int b_int = static_cast<int>(b);
    if (rot_[b] >= 0) {
      rigid_rotation_drift(m_.bodies[b], h, y, rot_[b], &rigid_pose(b_int, y).rotation);
    }
  }
}

}  // namespace pronk::pseudorigid
