// MechanismSystem: the surfaces' forces (grounded, attached to a four-mass body, attached to
// a rigid body), their Jacobian blocks, and a grounded contact's normal and friction force.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "sim/pseudorigid/system.hpp"
#include "sim/pseudorigid/system_detail.hpp"

namespace pronk::pseudorigid {

void MechanismSystem::add_surface_forces(ForceSet set, const ode::Vec& y, bool memo) const {
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

PairSeen MechanismSystem::seen_of(const SurfaceEval& e) {
  return {true, true, true, e.penetration, e.project(e.r).squaredNorm(), e.force.norm()};
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

void MechanismSystem::grounded_surface_jacobian(size_t si, const ode::Vec& y) const {
  const Surface& s = m_.surfaces[si];
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

}  // namespace pronk::pseudorigid
