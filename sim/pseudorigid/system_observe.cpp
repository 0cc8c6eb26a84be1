// MechanismSystem's error norm and observation: the body-level error norm, energies, power
// flows, accuracy monitors and surface forces of a state.
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/pseudorigid/system.hpp"
#include "sim/pseudorigid/system_detail.hpp"

namespace pronk::pseudorigid {

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

}  // namespace pronk::pseudorigid
