// MechanismSystem: the connections' forces, and how a force at a node reaches the masses
// that carry it (a ghost point's barycentric or minimum-norm transfer, a rigid body's force
// and torque).
#include <array>

#include "sim/pseudorigid/system.hpp"
#include "sim/pseudorigid/system_detail.hpp"

namespace pronk::pseudorigid {

void MechanismSystem::add_connection_forces(ForceSet set, const ode::Vec& y, bool memo) const {
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

}  // namespace pronk::pseudorigid
