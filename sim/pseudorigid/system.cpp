#include "sim/pseudorigid/system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/ode/difference_jacobian.hpp"
#include "sim/pseudorigid/rigid_body.hpp"

namespace pronk::pseudorigid {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Vector3d seg(const ode::Vec& y, int i) { return y.segment<3>(i); }

}  // namespace

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

namespace {

/// |l - l0| / l0 of a connection with rest length l0 > 0 and length l; u, when given, is
/// its stored energy k (l - l0)^2 / 2, from which |l - l0| follows without a second norm.
double connection_strain(const Connection& c, double l0, double l, double u = -1.0) {
  if (c.stiffness > 0.0) {
    if (u < 0.0) u = connection_energy_at(c, l0, l);
    return std::sqrt(2.0 * u / c.stiffness) / l0;
  }
  return std::abs(l - l0) / l0;
}

}  // namespace

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
  switch (n.kind) {
    case NodeRef::Kind::kMass:
      return seg(y, 6 * n.index);
    case NodeRef::Kind::kGhost: {
      const GhostPoint& g = m_.ghost_points[n.index];
      const int f = m_.bodies[g.body].first_mass;
      if (rot_[g.body] >= 0) return seg(y, 6 * f) + rigid_pose(g.body, y).rotation * g.local;
      Vector3d x = Vector3d::Zero();
      for (int i = 0; i < 4; ++i) x += g.weights[i] * seg(y, 6 * (f + i));
      return x;
    }
    case NodeRef::Kind::kAnchor:
      return m_.anchors[n.index].position;
  }
  return Vector3d::Zero();
}

Vector3d MechanismSystem::point_velocity(const NodeRef& n, const ode::Vec& y) const {
  switch (n.kind) {
    case NodeRef::Kind::kMass:
      return seg(y, 6 * n.index + 3) * inv_mass_[n.index];
    case NodeRef::Kind::kGhost: {
      const GhostPoint& g = m_.ghost_points[n.index];
      const int f = m_.bodies[g.body].first_mass;
      if (rot_[g.body] >= 0) {
        const RigidState& k = rigid_state(g.body, y);
        return seg(y, 6 * f + 3) * inv_mass_[f] + k.omega.cross(k.rotation * g.local);
      }
      Vector3d v = Vector3d::Zero();
      for (int i = 0; i < 4; ++i) v += g.weights[i] * inv_mass_[f + i] * seg(y, 6 * (f + i) + 3);
      return v;
    }
    case NodeRef::Kind::kAnchor:
      return Vector3d::Zero();
  }
  return Vector3d::Zero();
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

int MechanismSystem::transfers(const NodeRef& n, std::array<Transfer, 4>& out) const {
  switch (n.kind) {
    case NodeRef::Kind::kMass:
      out[0] = {n.index, Matrix3d::Identity()};
      return 1;
    case NodeRef::Kind::kGhost: {
      const GhostPoint& g = m_.ghost_points[n.index];
      const Matrix3d& r = frames_[g.body].rotation;
      const bool bary = m_.simulation.ghost_transfer == GhostTransfer::kBarycentric;
      for (int i = 0; i < 4; ++i) {
        out[i] = {m_.bodies[g.body].first_mass + i,
                  bary ? Matrix3d(g.weights[i] * Matrix3d::Identity())
                       : Matrix3d(r * g.transfer[i] * r.transpose())};
      }
      return 4;
    }
    case NodeRef::Kind::kAnchor:
      return 0;
  }
  return 0;
}

void MechanismSystem::apply(const NodeRef& n, const Vector3d& f) const {
  if (n.kind == NodeRef::Kind::kMass) {
    force_.segment<3>(3 * n.index) += f;
    return;
  }
  if (rigid_node(n)) {
    const GhostPoint& g = m_.ghost_points[n.index];
    force_.segment<3>(3 * m_.bodies[g.body].first_mass) += f;
    torque_[g.body] += (frames_[g.body].rotation * g.local).cross(f);
    return;
  }
  if (n.kind == NodeRef::Kind::kGhost &&
      m_.simulation.ghost_transfer == GhostTransfer::kBarycentric) {
    const GhostPoint& g = m_.ghost_points[n.index];
    const int first = m_.bodies[g.body].first_mass;
    for (int i = 0; i < 4; ++i) force_.segment<3>(3 * (first + i)) += g.weights[i] * f;
    return;
  }
  std::array<Transfer, 4> tr;
  const int k = transfers(n, tr);
  for (int i = 0; i < k; ++i) force_.segment<3>(3 * tr[i].mass) += tr[i].t * f;
}

bool MechanismSystem::surface_gap(size_t si, const NodeRef& n, const ode::Vec& y,
                                  SurfaceEval& e) const {
  const Surface& s = m_.surfaces[si];
  const SurfaceInputs& in = in_->surfaces[si];
  const Vector3d p =
      s.body >= 0 ? node_position(NodeRef{NodeRef::Kind::kGhost, s.ghost}, y) : s.point;
  e.dir = s.body >= 0 ? Vector3d(frames_[s.body].rotation * in.direction) : in.direction;
  e.r = node_position(n, y) - p;
  e.type = in.type;
  if (in.type == SurfaceType::kPlane && e.dir.dot(e.r) >= 0.0 && !in.bilateral) return false;
  e.penetration = penetration_of(in.type, e.dir, e.r);
  return true;
}

MechanismSystem::SurfaceEval MechanismSystem::eval_surface(size_t si, const NodeRef& n,
                                                           const ode::Vec& y, ForceSet set) const {
  const Surface& s = m_.surfaces[si];
  SurfaceEval e;
  // The velocity enters only the damper and the friction.
  const bool moving = set == ForceSet::kAll && (s.damping != 0.0 || s.friction != 0.0);
  if (moving) {
    const Vector3d vp = s.body >= 0 && s.damping != 0.0
                            ? node_velocity(NodeRef{NodeRef::Kind::kGhost, s.ghost}, y)
                            : Vector3d::Zero();
    e.v = node_velocity(n, y) - vp;
  }
  if (!surface_gap(si, n, y, e)) return e;
  e.active = true;
  e.force = -e.project(s.stiffness * e.r + s.damping * e.v);
  if (s.friction > 0.0) {  // grounded planes only (the loader enforces it)
    e.normal = std::max(0.0, e.dir.dot(e.force));
    const Vector3d vt = e.v - e.dir * e.dir.dot(e.v);
    e.friction =
        (-s.friction * e.normal / std::sqrt(vt.squaredNorm() + s.slip_velocity * s.slip_velocity)) *
        vt;
    e.force += e.friction;
  }
  return e;
}

namespace {

/// A body-attached surface's direction torque tau = -dU/dtheta [N m] for a node at r from the
/// surface's ghost point (in: its run-time inputs; dir: the world direction); false when a
/// one-sided plane is not touched.
bool attached_torque(const Surface& s, const SurfaceInputs& in, const Vector3d& dir,
                     const Vector3d& r, Vector3d& tau) {
  tau = Vector3d::Zero();
  switch (in.type) {
    case SurfaceType::kPlane:
      if (dir.dot(r) >= 0.0 && !in.bilateral) return false;
      tau = -s.stiffness * dir.dot(r) * dir.cross(r);
      break;
    case SurfaceType::kLine:
      tau = s.stiffness * dir.dot(r) * dir.cross(r);
      break;
    case SurfaceType::kPoint:
      break;
  }
  return true;
}

}  // namespace

void MechanismSystem::attached_surface_forces(size_t si, const NodeRef& n, const ode::Vec& y,
                                              ForceSet set,
                                              std::vector<std::pair<int, Vector3d>>& out,
                                              const BodyFrame* known_frame,
                                              const std::array<Matrix3d, 4>* known_omega) const {
  const Surface& s = m_.surfaces[si];
  const SurfaceInputs& in = in_->surfaces[si];
  const Body& body = m_.bodies[s.body];
  const GhostPoint& gp = m_.ghost_points[s.ghost];
  const BodyFrame& frame = known_frame != nullptr ? *known_frame : fitted_frame(s.body, y);
  const Matrix3d& rot = frame.rotation;
  const NodeRef g{NodeRef::Kind::kGhost, s.ghost};
  const Vector3d dir = rot * in.direction;
  const Vector3d r = node_position(n, y) - node_position(g, y);
  const Vector3d v = set == ForceSet::kConservative
                         ? Vector3d::Zero()
                         : Vector3d(node_velocity(n, y) - node_velocity(g, y));
  Vector3d tau;  // -dU/dtheta through the direction [N m]
  if (!attached_torque(s, in, dir, r, tau)) return;
  const Vector3d force = -project_onto(in.type, dir, s.stiffness * r + s.damping * v);
  if (n.kind == NodeRef::Kind::kMass) {
    out.emplace_back(n.index, force);
  } else if (n.kind == NodeRef::Kind::kGhost) {
    const GhostPoint& gn = m_.ghost_points[n.index];
    const int fn = m_.bodies[gn.body].first_mass;
    for (int i = 0; i < 4; ++i) out.emplace_back(fn + i, gn.weights[i] * force);
  }
  std::array<Matrix3d, 4> computed;
  const std::array<Matrix3d, 4>* omega = known_omega;
  if (in.type != SurfaceType::kPoint && omega == nullptr) {
    computed = attitude_derivative(frame, body.local);
    omega = &computed;
  }
  const Vector3d tau_body = rot.transpose() * tau;
  for (int i = 0; i < 4; ++i) {
    Vector3d f = -gp.weights[i] * force;
    if (in.type != SurfaceType::kPoint) f += (*omega)[i].transpose() * tau_body;
    out.emplace_back(body.first_mass + i, f);
  }
}

void MechanismSystem::attached_surfaces_jacobian(int b, const ode::Vec& y) const {
  // The active (surface, node) pairs on body b, and the masses they involve: the
  // body's four (their motion turns the surfaces) and the constrained nodes'.
  std::vector<std::pair<size_t, NodeRef>> pairs;  // (surface, node)
  bool damped = false;
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    const Surface& s = m_.surfaces[si];
    if (s.body != b) continue;
    for (const NodeRef& n : held_nodes(si)) {
      if (!eval_surface(si, n, y, ForceSet::kAll).active) continue;
      pairs.emplace_back(si, n);
      damped = damped || s.damping > 0.0;
    }
  }
  if (pairs.empty()) return;
  const Body& body = m_.bodies[b];
  const int fb = body.first_mass;
  std::vector<int> masses;
  for (int i = 0; i < 4; ++i) masses.push_back(fb + i);
  for (const auto& pair : pairs) {
    const NodeRef& n = pair.second;
    if (n.kind == NodeRef::Kind::kMass) {
      masses.push_back(n.index);
    } else if (n.kind == NodeRef::Kind::kGhost) {
      const int fn = m_.bodies[m_.ghost_points[n.index].body].first_mass;
      for (int i = 0; i < 4; ++i) masses.push_back(fn + i);
    }
  }
  std::sort(masses.begin(), masses.end());
  masses.erase(std::unique(masses.begin(), masses.end()), masses.end());
  // Forward differences, one column at a time, against the unperturbed forces of the
  // pairs the column moves. Only a position column of one of the body's own masses
  // turns the frame; it is refitted from the unperturbed frame (Newton converges in
  // one or two steps from there). The step sqrt(eps) (1 + |y|) balances truncation
  // and round-off at ~1e-8 relative, far below what the stiff steppers need.
  ode::Vec yp = y;
  std::vector<std::pair<int, Vector3d>> fp;
  std::vector<Vector3d> diff(m_.masses.size());
  const BodyFrame& frame0 = frames_[b];
  const std::array<Matrix3d, 4> omega0 = attitude_derivative(frame0, body.local);
  auto moves_with = [&](const NodeRef& n, int mass) {
    if (n.kind == NodeRef::Kind::kMass) return n.index == mass;
    if (n.kind != NodeRef::Kind::kGhost) return false;
    const int fn = m_.bodies[m_.ghost_points[n.index].body].first_mass;
    return mass >= fn && mass < fn + 4;
  };
  // Unperturbed forces per pair.
  std::vector<std::vector<std::pair<int, Vector3d>>> base(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    attached_surface_forces(pairs[k].first, pairs[k].second, y, ForceSet::kAll, base[k], &frame0,
                            &omega0);
  }
  // Momenta enter only through the dampers: without one, position columns suffice.
  const int columns = damped ? 6 : 3;
  const double step = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int mass : masses) {
    // All pairs depend on the body's own masses; the others' forces do not change with
    // another mass and difference to zero.
    const bool own = mass >= fb && mass < fb + 4;
    for (int c = 0; c < columns; ++c) {
      const int col = 6 * mass + c;
      yp[col] = y[col] + step * (1.0 + std::abs(y[col]));
      const double h = yp[col] - y[col];  // exactly representable
      BodyFrame frame = frame0;
      std::array<Matrix3d, 4> omega = omega0;
      if (own && c < 3) {
        std::array<Vector3d, 4> x;
        for (int i = 0; i < 4; ++i) x[i] = seg(yp, 6 * (fb + i));
        frame = fit_attitude(x, body.local, &frame0.rotation);
        omega = attitude_derivative(frame, body.local);
      }
      for (int t : masses) diff[t].setZero();
      for (size_t k = 0; k < pairs.size(); ++k) {
        if (!own && !moves_with(pairs[k].second, mass)) continue;
        fp.clear();
        attached_surface_forces(pairs[k].first, pairs[k].second, yp, ForceSet::kAll, fp, &frame,
                                &omega);
        for (const auto& [t, f] : fp) diff[t] += f;
        for (const auto& [t, f] : base[k]) diff[t] -= f;
      }
      yp[col] = y[col];
      for (int t : masses) {
        const Vector3d d = diff[t] / h;
        for (int k = 0; k < 3; ++k) {
          if (d[k] != 0.0) triplets_.emplace_back(6 * t + 3 + k, col, d[k]);
        }
      }
    }
  }
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
  bool zero_length = false;
  for (size_t i = 0; i < m_.connections.size(); ++i) {
    const Connection& c = m_.connections[i];
    const Vector3d d = node_position(c.a, y) - node_position(c.b, y);
    const Vector3d v = set == ForceSet::kConservative && c.kind != ConnectionClass::kActuator
                           ? Vector3d::Zero()
                           : Vector3d(node_velocity(c.a, y) - node_velocity(c.b, y));
    const ConnectionForce cf =
        connection_force(c, in_->rest_length[i], d, v, m_.simulation.zero_length_epsilon, false);
    if (memo) memo_.length[i] = cf.length;
    zero_length = zero_length || cf.zero_length;
    apply(c.a, cf.force);
    apply(c.b, -cf.force);
  }
  if (zero_length) ++zero_length_;
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    const Surface& s = m_.surfaces[si];
    // observe() reads the pairs whose force is the conservative one.
    const bool known = memo && s.damping == 0.0 && s.friction == 0.0;
    for (const NodeRef& n : held_nodes(si)) {
      PairSeen* seen = memo ? &memo_.pairs.emplace_back() : nullptr;
      if (s.body < 0) {
        const SurfaceEval e = eval_surface(si, n, y, set);
        if (e.active) apply(n, e.force);
        if (memo) *seen = known && e.active ? seen_of(e) : PairSeen{known, true, e.active};
        continue;
      }
      if (rot_[s.body] >= 0) {
        if (known) seen->known = seen->geometric = true;
        rigid_surface_forces(si, n, y, set, known ? seen : nullptr);
        continue;
      }
      attached_.clear();  // (an inactive plane adds nothing)
      attached_surface_forces(si, n, y, set, attached_, &frames_[s.body], &dframes_[s.body]);
      for (const auto& [mass, f] : attached_) force_.segment<3>(3 * mass) += f;
    }
  }
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

void MechanismSystem::begin_memo(const ode::Vec& y) const {
  memo_.valid = false;
  memo_.y = y;
  memo_.surfaces = in_->surfaces;
  memo_.length.resize(m_.connections.size());
  memo_.pairs.clear();
}

PairSeen MechanismSystem::seen_of(const SurfaceEval& e) {
  return {true, true, true, e.penetration, e.project(e.r).squaredNorm(), e.force.norm()};
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

const MechanismSystem::RigidState& MechanismSystem::rigid_pose(int b, const ode::Vec& y) const {
  RigidState& k = rigid_[static_cast<size_t>(b)];
  const int r = rot_[static_cast<size_t>(b)];
  // The rotation follows the quaternion alone: an impulse (a new angular momentum) keeps it.
  if (y[r] != k.key[0] || y[r + 1] != k.key[1] || y[r + 2] != k.key[2] || y[r + 3] != k.key[3]) {
    k.key.head<4>() = y.segment<4>(r);
    k.key.tail<3>().setConstant(std::numeric_limits<double>::quiet_NaN());  // omega stale
    k.rotation = rigid_rotation(y, r);
    k.inverse_inertia = rigid_inverse_inertia(m_.bodies[static_cast<size_t>(b)], k.rotation);
  }
  return k;
}

const MechanismSystem::RigidState& MechanismSystem::rigid_state(int b, const ode::Vec& y) const {
  rigid_pose(b, y);
  RigidState& k = rigid_[static_cast<size_t>(b)];
  const int r = rot_[static_cast<size_t>(b)];
  if (!(y[r + 4] == k.key[4] && y[r + 5] == k.key[5] && y[r + 6] == k.key[6])) {
    k.key.tail<3>() = y.segment<3>(r + 4);
    k.omega = rigid_omega(m_.bodies[static_cast<size_t>(b)], k.rotation, seg(y, r + 4));
  }
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

void MechanismSystem::rigid_surface_forces(size_t si, const NodeRef& n, const ode::Vec& y,
                                           ForceSet set, PairSeen* seen) const {
  const Surface& s = m_.surfaces[si];
  const SurfaceInputs& in = in_->surfaces[si];
  const Matrix3d& rot = frames_[s.body].rotation;
  const NodeRef g{NodeRef::Kind::kGhost, s.ghost};
  const Vector3d dir = rot * in.direction;
  const Vector3d r = node_position(n, y) - node_position(g, y);
  const Vector3d v = set == ForceSet::kConservative
                         ? Vector3d::Zero()
                         : Vector3d(node_velocity(n, y) - node_velocity(g, y));
  Vector3d tau;  // -dU/dtheta through the turning direction [N m]
  if (!attached_torque(s, in, dir, r, tau)) return;
  const Vector3d force = -project_onto(in.type, dir, s.stiffness * r + s.damping * v);
  apply(n, force);
  apply(g, -force);
  torque_[s.body] += tau;
  if (seen != nullptr) {  // surface_gap's and observe()'s expressions, bit for bit
    *seen = {true,
             true,
             true,
             penetration_of(in.type, dir, r),
             project_onto(in.type, dir, r).squaredNorm(),
             force.norm()};
  }
}

void MechanismSystem::add_node_force(const NodeRef& n, const Vector3d& f, const ode::Vec& y,
                                     ode::Vec& dydt) const {
  if (n.kind == NodeRef::Kind::kMass) {
    dydt.segment<3>(6 * n.index + 3) += f;
  } else if (rigid_node(n)) {
    const GhostPoint& g = m_.ghost_points[n.index];
    const int first = m_.bodies[g.body].first_mass;
    dydt.segment<3>(6 * first + 3) += f;
    dydt.segment<3>(rot_[g.body] + 4) += (node_position(n, y) - seg(y, 6 * first)).cross(f);
  } else if (n.kind == NodeRef::Kind::kGhost) {
    const GhostPoint& g = m_.ghost_points[n.index];
    const int first = m_.bodies[g.body].first_mass;
    for (int i = 0; i < 4; ++i) dydt.segment<3>(6 * (first + i) + 3) += g.weights[i] * f;
  }
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

void MechanismSystem::conservative_rhs(double /*t*/, const ode::Vec& y, ode::Vec& dydt) const {
  evaluate(ForceSet::kConservative, y, dydt);
}

double MechanismSystem::inverse_mass(const NodeRef& n) const {
  switch (n.kind) {
    case NodeRef::Kind::kMass:
      return inv_mass_[n.index];
    case NodeRef::Kind::kGhost: {
      const GhostPoint& g = m_.ghost_points[n.index];
      const int f = m_.bodies[g.body].first_mass;
      if (rot_[g.body] >= 0) return inv_mass_[f];  // translation (inverse_mass_along: rotation)
      double w = 0.0;
      for (int i = 0; i < 4; ++i) w += g.weights[i] * g.weights[i] * inv_mass_[f + i];
      return w;
    }
    case NodeRef::Kind::kAnchor:
      return 0.0;
  }
  return 0.0;
}

double MechanismSystem::inverse_mass_along(const NodeRef& n, const ode::Vec& y,
                                           const Vector3d& d) const {
  if (!rigid_node(n)) return inverse_mass(n);
  const GhostPoint& g = m_.ghost_points[n.index];
  const Body& b = m_.bodies[g.body];
  const RigidState& k = rigid_pose(g.body, y);
  const Vector3d a = (k.rotation * g.local).cross(d);
  return inv_mass_[b.first_mass] * d.squaredNorm() + a.dot(k.inverse_inertia * a);
}

void MechanismSystem::add_impulse(const NodeRef& n, const Vector3d& j, ode::Vec& y) const {
  if (n.kind == NodeRef::Kind::kMass) {
    y.segment<3>(6 * n.index + 3) += j;
  } else if (rigid_node(n)) {
    const GhostPoint& g = m_.ghost_points[n.index];
    const int first = m_.bodies[g.body].first_mass;
    const Vector3d arm = rigid_pose(g.body, y).rotation * g.local;
    y.segment<3>(6 * first + 3) += j;
    y.segment<3>(rot_[g.body] + 4) += arm.cross(j);
  } else if (n.kind == NodeRef::Kind::kGhost) {
    const GhostPoint& g = m_.ghost_points[n.index];
    const int f = m_.bodies[g.body].first_mass;
    for (int i = 0; i < 4; ++i) y.segment<3>(6 * (f + i) + 3) += g.weights[i] * j;
  }
}

namespace {

Vector3d unit_or_zero(const Vector3d& u) {
  const double n = u.norm();
  return n > 0.0 ? Vector3d(u / n) : Vector3d::Zero();
}

/// The speed s >= 0 with s + a s / sqrt(s^2 + vs^2) = u (u >= 0, a >= 0, vs > 0): backward
/// Euler of regularised Coulomb friction. The left side g(s) + u is increasing and concave,
/// so Newton from a point left of the root climbs monotonically to it. Start: the larger of
/// the viscous solution u / (1 + a / vs) and the sliding one u - a, both left of the root
/// (s / sqrt(s^2 + vs^2) lies below s / vs and below 1) and each exact in its regime.
double friction_speed(double u, double a, double vs) {
  double s = std::max(u / (1.0 + a / vs), u - a);
  for (int it = 0; it < 100; ++it) {
    const double r = std::sqrt(s * s + vs * vs);
    const double g = s + a * s / r - u;
    if (g >= -1e-15 * u) break;
    const double next = s - g / (1.0 + a * vs * vs / (r * r * r));
    if (!(next > s)) break;  // converged to round-off
    s = next;
  }
  return std::min(s, u);
}

}  // namespace

double MechanismSystem::dissipate(double /*t*/, double h, const ode::Vec& y_ref,
                                  ode::Vec& y) const {
  if (!has_power_flows_) return 0.0;
  dissipate_before_ = y;
  dissipate_connections(h, y);
  dissipate_surfaces(h, y);
  // Nothing acted (a flight phase without dampers): the booking is zero.
  if ((y.array() == dissipate_before_.array()).all()) return 0.0;
  return booked_dissipation(y_ref, dissipate_before_, y);
}

void MechanismSystem::dissipate_connections(double h, ode::Vec& y) const {
  for (const Connection& c : m_.connections) {
    if (c.kind == ConnectionClass::kActuator) continue;
    if (c.damping == 0.0 && c.friction == 0.0 && c.drag == 0.0) continue;
    double w = inverse_mass(c.a) + inverse_mass(c.b);
    if (!(w > 0.0)) continue;
    // A rigid body's ghost point answers an impulse by its direction (its rotation).
    const bool rigid = rigid_node(c.a) || rigid_node(c.b);
    auto along = [&](const Vector3d& d) {
      if (rigid) w = inverse_mass_along(c.a, y, d) + inverse_mass_along(c.b, y, d);
    };
    // Each term: the relative velocity u changes by w J under the impulse J on a (-J on b).
    auto push = [&](const Vector3d& j) {
      add_impulse(c.a, j, y);
      add_impulse(c.b, -j, y);
    };
    if (c.damping > 0.0) {
      const Vector3d d = node_position(c.a, y) - node_position(c.b, y);
      const double l = d.norm();
      if (l >= m_.simulation.zero_length_epsilon) {
        const Vector3d e = d / l;
        along(e);
        const double u = e.dot(node_velocity(c.a, y) - node_velocity(c.b, y));
        push((-h * c.damping * u / (1.0 + h * c.damping * w)) * e);
      }
    }
    if (c.friction > 0.0) {
      const Vector3d u = node_velocity(c.a, y) - node_velocity(c.b, y);
      along(unit_or_zero(u));
      push((-h * c.friction / (1.0 + h * c.friction * w)) * u);
    }
    if (c.drag > 0.0) {
      // |u_new| + h q w |u_new|^2 = |u|.
      const Vector3d u = node_velocity(c.a, y) - node_velocity(c.b, y);
      along(unit_or_zero(u));
      const double s = u.norm();
      const double a = h * c.drag * w;
      if (s > 0.0 && a > 0.0) {
        const double sn = 2.0 * s / (1.0 + std::sqrt(1.0 + 4.0 * a * s));
        push(((sn - s) / (w * s)) * u);
      }
    }
  }
}

void MechanismSystem::dissipate_surfaces(double h, ode::Vec& y) const {
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    const Surface& s = m_.surfaces[si];
    const SurfaceInputs& in = in_->surfaces[si];
    if (s.damping == 0.0 && s.friction == 0.0) continue;
    Matrix3d rot = Matrix3d::Identity();
    NodeRef g{NodeRef::Kind::kAnchor, -1};
    double wg = 0.0;
    if (s.body >= 0) {
      rot = fitted_frame(s.body, y).rotation;
      g = NodeRef{NodeRef::Kind::kGhost, s.ghost};
      wg = inverse_mass(g);
    }
    const Vector3d dir = rot * in.direction;
    const Vector3d p = s.body >= 0 ? node_position(g, y) : s.point;
    for (const NodeRef& n : held_nodes(si)) {
      const Vector3d r = node_position(n, y) - p;
      const bool plane = in.type == SurfaceType::kPlane;
      const double height = dir.dot(r);
      if (plane && height >= 0.0 && !in.bilateral) continue;
      double w = inverse_mass(n) + wg;
      if (!(w > 0.0)) continue;
      Vector3d u = node_velocity(n, y);
      if (s.body >= 0) u -= node_velocity(g, y);
      // A rigid body's ghost point answers an impulse by its direction (its rotation).
      const bool rigid = rigid_node(n) || (s.body >= 0 && rigid_node(g));
      auto along = [&](const Vector3d& d) {
        if (!rigid) return w;
        return inverse_mass_along(n, y, d) + (s.body >= 0 ? inverse_mass_along(g, y, d) : 0.0);
      };
      // The damper acts on the constrained components: the normal one of a plane, the two
      // across a line, all three at a point.
      Vector3d j = Vector3d::Zero();
      double un = dir.dot(u);
      if (rigid) {
        w = along(plane                           ? dir
                  : in.type == SurfaceType::kLine ? unit_or_zero(u - un * dir)
                                                  : unit_or_zero(u));
      }
      const double damp = h * s.damping / (1.0 + h * s.damping * w);
      if (plane) {
        j = (-damp * un) * dir;
        un -= damp * w * un;
      } else if (in.type == SurfaceType::kLine) {
        j = -damp * (u - un * dir);
      } else {
        j = -damp * u;
      }
      if (s.friction > 0.0) {
        // Normal force with the damped normal velocity, then backward Euler of the
        // regularised Coulomb law along the tangential velocity (its direction is kept).
        const double normal = std::max(0.0, -s.stiffness * height - s.damping * un);
        const Vector3d ut = u - dir * dir.dot(u);
        const double speed = ut.norm();
        if (normal > 0.0 && speed > 0.0) {
          if (rigid) w = along(ut / speed);
          const double sn = friction_speed(speed, h * s.friction * normal * w, s.slip_velocity);
          j += ((sn - speed) / (w * speed)) * ut;
        }
      }
      add_impulse(n, j, y);
      if (s.body >= 0) add_impulse(g, -j, y);
    }
  }
}

double MechanismSystem::booked_dissipation(const ode::Vec& y_ref, const ode::Vec& y_before,
                                           const ode::Vec& y) const {
  // The energy balance of the step: with the momentum changes dP_j of the masses,
  // -sum dP_j . (v_ref_j + dP_j / 2 m_j) (see the header).
  double dissipated = 0.0;
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) {
    const Vector3d dp = seg(y, 6 * j + 3) - seg(y_before, 6 * j + 3);
    dissipated -= dp.dot(seg(y_ref, 6 * j + 3) + 0.5 * dp) * inv_mass_[j];
  }
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    const int r = rot_[b];
    if (r < 0) continue;  // the rotation: -dL . I_w^-1 (L_ref + dL / 2)
    const Vector3d dl = seg(y, r + 4) - seg(y_before, r + 4);
    const Matrix3d& iw = rigid_pose(static_cast<int>(b), y).inverse_inertia;
    dissipated -= dl.dot(iw * (seg(y_ref, r + 4) + 0.5 * dl));
  }
  return dissipated;
}

void MechanismSystem::correct_step(const ode::Vec& y0, ode::Vec& y1) const {
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    const Surface& s = m_.surfaces[si];
    const SurfaceInputs& in = in_->surfaces[si];
    if (s.body >= 0 || in.type != SurfaceType::kPlane || in.bilateral) continue;
    for (const NodeRef& n : held_nodes(si)) {
      const double z0 = in.direction.dot(node_position(n, y0) - s.point);
      const double z1 = in.direction.dot(node_position(n, y1) - s.point);
      if ((z0 < 0.0) == (z1 < 0.0)) continue;  // no kink crossed: exact already
      const double w = inverse_mass_along(n, y1, in.direction);
      if (!(w > 0.0)) continue;
      // Energy the kicks' trapezoidal contact work gave beyond the exact one [J].
      const double f0 = s.stiffness * std::max(0.0, -z0), f1 = s.stiffness * std::max(0.0, -z1);
      const double u0 = 0.5 * s.stiffness * std::min(0.0, z0) * std::min(0.0, z0);
      const double u1 = 0.5 * s.stiffness * std::min(0.0, z1) * std::min(0.0, z1);
      const double excess = 0.5 * (f0 + f1) * (z1 - z0) + (u1 - u0);
      // Impulse J along the normal with J u + w J^2 / 2 = -excess (u: normal velocity).
      const double u = in.direction.dot(node_velocity(n, y1));
      const double disc = u * u - 2.0 * w * excess;
      const double j = disc >= 0.0 ? (-u + std::copysign(std::sqrt(disc), u)) / w : -u / w;
      add_impulse(n, j * in.direction, y1);
    }
  }
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

// ---------------------------------------------------------------------------
// Jacobian

void MechanismSystem::add_block(int row, int col, const Matrix3d& b) const {
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      if (b(i, k) != 0.0) triplets_.emplace_back(row + i, col + k, b(i, k));
    }
  }
}

/// d(force on target)/d(state) for a force depending on the position (kx) and
/// velocity (kv) of `source`.
void MechanismSystem::jac_force(const NodeRef& target, const NodeRef& source, const Matrix3d& kx,
                                const Matrix3d& kv) const {
  std::array<Transfer, 4> tr;
  const int nt = transfers(target, tr);
  int src_mass[4];
  double src_w[4];
  int ns = 0;
  if (source.kind == NodeRef::Kind::kMass) {
    src_mass[0] = source.index;
    src_w[0] = 1.0;
    ns = 1;
  } else if (source.kind == NodeRef::Kind::kGhost) {
    const GhostPoint& g = m_.ghost_points[source.index];
    for (int i = 0; i < 4; ++i) {
      src_mass[i] = m_.bodies[g.body].first_mass + i;
      src_w[i] = g.weights[i];
    }
    ns = 4;
  }
  for (int a = 0; a < nt; ++a) {
    const Matrix3d tx = tr[a].t * kx, tv = tr[a].t * kv;
    for (int b = 0; b < ns; ++b) {
      const int k = src_mass[b];
      add_block(6 * tr[a].mass + 3, 6 * k, src_w[b] * tx);
      add_block(6 * tr[a].mass + 3, 6 * k + 3, (src_w[b] * inv_mass_[k]) * tv);
    }
  }
}

/// d(force on target)/d(x) for a force that changes by d * omega_body of `body`.
void MechanismSystem::jac_rotation(const NodeRef& target, int body, const Matrix3d& d) const {
  std::array<Transfer, 4> tr;
  const int nt = transfers(target, tr);
  const int f = m_.bodies[body].first_mass;
  for (int a = 0; a < nt; ++a) {
    const Matrix3d td = tr[a].t * d;
    for (int k = 0; k < 4; ++k) add_block(6 * tr[a].mass + 3, 6 * (f + k), td * dframes_[body][k]);
  }
}

/// Rotation dependence of the ghost-point transfer itself: F_i = R G_i R^T F.
void MechanismSystem::jac_transfer(const NodeRef& target, const Vector3d& force) const {
  if (target.kind != NodeRef::Kind::kGhost) return;
  if (m_.simulation.ghost_transfer == GhostTransfer::kBarycentric) return;  // constant weights
  const GhostPoint& g = m_.ghost_points[target.index];
  const Matrix3d& r = frames_[g.body].rotation;
  const Vector3d fb = r.transpose() * force;
  const int f = m_.bodies[g.body].first_mass;
  for (int i = 0; i < 4; ++i) {
    const Matrix3d d = r * (g.transfer[i] * skew(fb) - skew(g.transfer[i] * fb));
    for (int k = 0; k < 4; ++k) add_block(6 * (f + i) + 3, 6 * (f + k), d * dframes_[g.body][k]);
  }
}

void MechanismSystem::jacobian(double t, const ode::Vec& y,
                               Eigen::SparseMatrix<double>& jac) const {
  if (any_rigid_) {  // a rigid body's rotation: forward differences of the whole RHS
    ode::difference_jacobian(*this, t, y, jac);
    return;
  }
  update_frames(y, true);
  triplets_.clear();
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) {
    for (int i = 0; i < 3; ++i) triplets_.emplace_back(6 * j + i, 6 * j + 3 + i, inv_mass_[j]);
  }
  for (size_t i = 0; i < m_.connections.size(); ++i) {
    const Connection& c = m_.connections[i];
    const Vector3d d = node_position(c.a, y) - node_position(c.b, y);
    const Vector3d v = node_velocity(c.a, y) - node_velocity(c.b, y);
    const ConnectionForce cf =
        connection_force(c, in_->rest_length[i], d, v, m_.simulation.zero_length_epsilon);
    jac_force(c.a, c.a, cf.d_dx, cf.d_dv);
    jac_force(c.a, c.b, -cf.d_dx, -cf.d_dv);
    jac_force(c.b, c.a, -cf.d_dx, -cf.d_dv);
    jac_force(c.b, c.b, cf.d_dx, cf.d_dv);
    jac_transfer(c.a, cf.force);
    jac_transfer(c.b, -cf.force);
  }
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    const Surface& s = m_.surfaces[si];
    if (s.body >= 0) continue;  // body-attached: attached_surfaces_jacobian, below
    for (const NodeRef& n : held_nodes(si)) {
      const SurfaceEval e = eval_surface(si, n, y, ForceSet::kAll);
      if (!e.active) continue;
      const Matrix3d proj = projector(e.type, e.dir);
      Matrix3d kx = -s.stiffness * proj, kv = -s.damping * proj;
      if (e.normal > 0.0) {
        // F_t = -mu N g(v), g = v_t / w, w = sqrt(|v_t|^2 + v_s^2), v_t = P v with
        // P = 1 - n n^T; dN/dx = -k n^T, dN/dv = -b n^T (n = dir, penetrating);
        // dg/dv = (P - g g^T P) / w = (P - v_t v_t^T / w^2) / w.
        const Vector3d& nn = e.dir;
        const Matrix3d p = Matrix3d::Identity() - nn * nn.transpose();
        const Vector3d vt = p * e.v;
        const double w2 = vt.squaredNorm() + s.slip_velocity * s.slip_velocity;
        const double w = std::sqrt(w2);
        const Vector3d g = vt / w;
        kx += (s.friction * s.stiffness) * g * nn.transpose();
        kv += (s.friction * s.damping) * g * nn.transpose() -
              (s.friction * e.normal / w) * (p - vt * vt.transpose() / w2);
      }
      jac_force(n, n, kx, kv);
    }
  }
  for (int b = 0; b < static_cast<int>(m_.bodies.size()); ++b) attached_surfaces_jacobian(b, y);
  for (const WorldForce& f : m_.world_forces) jac_transfer(f.node, f.force);
  auto body_force_jac = [&](const NodeRef& node, int body, const Vector3d& fb) {
    const Matrix3d& r = frames_[body].rotation;
    jac_rotation(node, body, -r * skew(fb));
    jac_transfer(node, r * fb);
  };
  for (const BodyForce& f : m_.body_forces) {
    if (active(f.t_start, f.t_end)) body_force_jac(f.node, f.body, f.force);
  }
  for (const ImpulseActuator& a : m_.impulse_actuators) {
    if (active(a.t_start, a.t_start + a.duration())) {
      body_force_jac(a.node, a.body, a.force * a.direction);
    }
  }
  const int n = dimension();
  jac.resize(n, n);
  jac.setFromTriplets(triplets_.begin(), triplets_.end());
}

// ---------------------------------------------------------------------------
// Error norm, energies, monitors

double MechanismSystem::error_norm(const ode::Vec& err, const ode::Vec& y0, const ode::Vec& y1,
                                   double rtol, double atol) const {
  double sum = 0.0;
  long count = 0;
  auto add = [&](double e, double scale) {
    const double q = e / (atol + rtol * scale);
    sum += q * q;
    ++count;
  };
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) {
    if (m_.masses[j].body >= 0 || m_.masses[j].dummy_of >= 0) continue;
    for (int i = 0; i < 6; ++i)
      add(err[6 * j + i], std::max(std::abs(y0[6 * j + i]), std::abs(y1[6 * j + i])));
  }
  for (size_t bi = 0; bi < m_.bodies.size(); ++bi) {
    const Body& b = m_.bodies[bi];
    if (b.rigid) {  // its states are body-level already: CoM, quaternion, angular momentum
      const int s = 6 * b.first_mass, r = rot_[bi];
      const double lscale = std::max(seg(y0, r + 4).norm(), seg(y1, r + 4).norm());
      for (int i = 0; i < 3; ++i) {
        add(err[s + i], std::max(std::abs(y0[s + i]), std::abs(y1[s + i])));
        add(err[s + 3 + i] / b.mass,
            std::max(seg(y0, s + 3).norm(), seg(y1, s + 3).norm()) / b.mass);
        add(err[r + 4 + i], lscale);
      }
      for (int i = 0; i < 4; ++i) add(err[r + i], 1.0);
      continue;
    }
    Vector3d c0 = Vector3d::Zero(), c1 = Vector3d::Zero(), dc = Vector3d::Zero();
    Vector3d p0 = Vector3d::Zero(), p1 = Vector3d::Zero(), dp = Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      const int s = 6 * (b.first_mass + i);
      c0 += 0.25 * seg(y0, s);
      c1 += 0.25 * seg(y1, s);
      dc += 0.25 * seg(err, s);
      p0 += seg(y0, s + 3);
      p1 += seg(y1, s + 3);
      dp += seg(err, s + 3);
    }
    // Small rotation and angular-velocity errors: least-squares fits of the
    // mass errors relative to the CoM, using the current arm r_i.
    Matrix3d g = Matrix3d::Zero();
    Vector3d rot = Vector3d::Zero(), rate = Vector3d::Zero(), w = Vector3d::Zero();
    const Vector3d vc = p1 / b.mass;
    for (int i = 0; i < 4; ++i) {
      const int s = 6 * (b.first_mass + i);
      const Vector3d r = seg(y1, s) - c1;
      g += r.squaredNorm() * Matrix3d::Identity() - r * r.transpose();
      rot += r.cross(seg(err, s) - dc);
      rate += r.cross((seg(err, s + 3) - 0.25 * dp) * inv_mass_[b.first_mass + i]);
      w += r.cross(seg(y1, s + 3) * inv_mass_[b.first_mass + i] - vc);
    }
    const Matrix3d gi = g.inverse();
    const Vector3d dtheta = gi * rot, domega = gi * rate, omega = gi * w;
    const double vscale = std::max(p0.norm(), p1.norm()) / b.mass;
    for (int i = 0; i < 3; ++i) {
      add(dc[i], std::max(std::abs(c0[i]), std::abs(c1[i])));
      add(dp[i] / b.mass, vscale);
      add(dtheta[i], 1.0);
      add(domega[i], omega.norm());
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

void MechanismSystem::observe(const ode::Vec& y, Energies* energies, StateMonitors* monitors,
                              std::vector<double>* surface_max) const {
  if (rhs_needs_frames_) update_frames(y, false);
  Energies e;
  StateMonitors mon;
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) {
    e.kinetic += 0.5 * seg(y, 6 * j + 3).squaredNorm() * inv_mass_[j];
    e.gravitational -= m_.masses[j].mass * m_.gravity.dot(seg(y, 6 * j));
  }
  for (size_t b = 0; b < m_.bodies.size(); ++b) {
    const int r = rot_[b];
    if (r < 0) continue;
    const Vector3d l = seg(y, r + 4);
    e.kinetic += 0.5 * l.dot(frame_inverse_inertia(b) * l);
  }
  for (const WorldForce& f : m_.world_forces) e.applied -= f.force.dot(node_position(f.node, y));
  const bool hit = memo_holds(y);  // the last conservative evaluation was at y's positions
  if (hit) ++memo_hits_;
  for (size_t i = 0; i < m_.connections.size(); ++i) {
    const Connection& c = m_.connections[i];
    const double l0 = in_->rest_length[i];
    const double l = hit ? memo_.length[i] : (node_position(c.a, y) - node_position(c.b, y)).norm();
    const double u = connection_energy_at(c, l0, l);
    switch (c.kind) {
      case ConnectionClass::kInternal:
        e.internal += u;
        if (l0 > 0.0) mon.max_strain = std::max(mon.max_strain, connection_strain(c, l0, l, u));
        break;
      case ConnectionClass::kLeg:
        e.leg += u;
        break;
      default:
        e.other += u;
        break;
    }
  }
  size_t pair = 0;
  for (size_t i = 0; i < m_.surfaces.size(); ++i) {
    const Surface& s = m_.surfaces[i];
    for (const NodeRef& n : held_nodes(i)) {
      const PairSeen* seen = hit ? &memo_.pairs[pair] : nullptr;
      ++pair;
      PairSeen p;
      if (seen != nullptr && (seen->known || (seen->geometric && !seen->touching))) {
        p = *seen;  // all of it, or that it does not touch
      } else {
        const SurfaceEval ev = eval_surface(i, n, y, ForceSet::kAll);
        if (ev.active) p = seen_of(ev);
      }
      if (!p.touching) continue;
      e.contact += 0.5 * s.stiffness * p.projected2;
      mon.max_penetration = std::max(mon.max_penetration, p.penetration);
      if (surface_max != nullptr) (*surface_max)[i] = std::max((*surface_max)[i], p.force);
    }
  }
  if (energies != nullptr) *energies = e;
  if (monitors != nullptr) *monitors = mon;
}

Energies MechanismSystem::energies(const ode::Vec& y) const {
  Energies e;
  observe(y, &e, nullptr, nullptr);
  return e;
}

PowerFlows MechanismSystem::power(const ode::Vec& y) const {
  PowerFlows p;
  if (!has_power_flows_) return p;
  if (rhs_needs_frames_) update_frames(y, false);
  for (size_t i = 0; i < m_.connections.size(); ++i) {
    const Connection& c = m_.connections[i];
    const Vector3d d = node_position(c.a, y) - node_position(c.b, y);
    const Vector3d v = node_velocity(c.a, y) - node_velocity(c.b, y);
    const ConnectionForce cf =
        connection_force(c, in_->rest_length[i], d, v, m_.simulation.zero_length_epsilon, false);
    p.dissipated -= cf.dissipative.dot(v);
    if (c.kind == ConnectionClass::kActuator) p.actuator += cf.force.dot(v);
  }
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    const Surface& s = m_.surfaces[si];
    for (const NodeRef& n : held_nodes(si)) {
      const SurfaceEval e = eval_surface(si, n, y, ForceSet::kAll);
      if (e.active) p.dissipated += s.damping * e.project(e.v).dot(e.v) - e.friction.dot(e.v);
    }
  }
  for (const BodyForce& f : m_.body_forces) {
    if (active(f.t_start, f.t_end)) {
      p.actuator += (frames_[f.body].rotation * f.force).dot(node_velocity(f.node, y));
    }
  }
  for (const ImpulseActuator& a : m_.impulse_actuators) {
    if (active(a.t_start, a.t_start + a.duration())) {
      p.actuator +=
          (frames_[a.body].rotation * (a.force * a.direction)).dot(node_velocity(a.node, y));
    }
  }
  return p;
}

StateMonitors MechanismSystem::monitors(const ode::Vec& y) const {
  // observe()'s monitors alone (the same expressions): no energies, no surface forces.
  if (rhs_needs_frames_) update_frames(y, false);
  StateMonitors mon;
  for (size_t i = 0; i < m_.connections.size(); ++i) {
    const Connection& c = m_.connections[i];
    const double l0 = in_->rest_length[i];
    if (c.kind != ConnectionClass::kInternal || !(l0 > 0.0)) continue;
    const Vector3d d = node_position(c.a, y) - node_position(c.b, y);
    mon.max_strain = std::max(mon.max_strain, connection_strain(c, l0, d.norm()));
  }
  SurfaceEval e;
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    for (const NodeRef& n : held_nodes(si)) {
      if (surface_gap(si, n, y, e))
        mon.max_penetration = std::max(mon.max_penetration, e.penetration);
    }
  }
  return mon;
}

std::vector<double> MechanismSystem::surface_forces(const ode::Vec& y) const {
  std::vector<double> out(m_.surfaces.size(), 0.0);
  observe(y, nullptr, nullptr, &out);
  return out;
}

MechanismSystem::Contact MechanismSystem::contact(int surface, const NodeRef& n,
                                                  const ode::Vec& y) const {
  const Surface& s = m_.surfaces[static_cast<size_t>(surface)];
  Contact c;
  if (s.body >= 0) return c;  // grounded planes only
  const SurfaceEval e = eval_surface(static_cast<size_t>(surface), n, y, ForceSet::kAll);
  if (!e.active) return c;
  c.normal = std::max(0.0, e.dir.dot(e.force - e.friction));
  c.friction = e.friction;
  return c;
}

double jacobian_check(const MechanismSystem& sys, double t, const ode::Vec& y, int* worst_row,
                      int* worst_col) {
  const int n = sys.dimension();
  Eigen::SparseMatrix<double> js;
  sys.jacobian(t, y, js);
  const Eigen::MatrixXd ja(js);
  Eigen::MatrixXd jf(n, n);
  ode::Vec yp = y, fp(n), fm(n);
  for (int i = 0; i < n; ++i) {
    const double h = 1e-6 * std::max(1e-3, std::abs(y[i]));
    yp[i] = y[i] + h;
    sys.rhs(t, yp, fp);
    yp[i] = y[i] - h;
    sys.rhs(t, yp, fm);
    yp[i] = y[i];
    jf.col(i) = (fp - fm) / (2.0 * h);
  }
  const double scale = std::max(1.0, ja.cwiseAbs().maxCoeff());
  Eigen::Index r = 0, c = 0;
  const double worst = (ja - jf).cwiseAbs().maxCoeff(&r, &c) / scale;
  if (worst_row) *worst_row = static_cast<int>(r);
  if (worst_col) *worst_col = static_cast<int>(c);
  return worst;
}

}  // namespace pronk::pseudorigid
