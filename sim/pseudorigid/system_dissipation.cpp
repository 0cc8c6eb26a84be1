// MechanismSystem's dissipation split for method verlet: the implicit impulses of dampers,
// friction and drag, their energy booking, and the contact correction of a step.
#include <algorithm>
#include <cmath>

#include "sim/pseudorigid/system.hpp"
#include "sim/pseudorigid/system_detail.hpp"

namespace pronk::pseudorigid {

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

}  // namespace pronk::pseudorigid
