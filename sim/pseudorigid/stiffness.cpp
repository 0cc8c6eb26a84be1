#include "sim/pseudorigid/stiffness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "sim/pseudorigid/attitude.hpp"
#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

StiffnessChoice choose_stiffness(Mechanism& m, const StiffnessSettings& s) {
  StiffnessChoice out;
  const double g = m.gravity.norm();
  double applied = 0.0;  // largest applied force anywhere [N]
  for (const auto& f : m.world_forces) applied = std::max(applied, f.force.norm());
  for (const auto& f : m.body_forces) applied = std::max(applied, f.force.norm());
  for (const auto& a : m.impulse_actuators) applied = std::max(applied, a.force);
  for (const auto& c : m.connections) {
    if (c.kind == ConnectionClass::kActuator) applied = std::max(applied, c.force_limit);
  }
  if (s.internal_auto) {
    out.internal_min = 1e300;
    for (size_t b = 0; b < m.bodies.size(); ++b) {
      const Body& body = m.bodies[b];
      std::array<Eigen::Vector3d, 4> x, v;
      double w = 0.0;  // initial angular speed [rad/s]
      if (body.rigid) {
        const Eigen::Matrix3d r = body.attitude0.toRotationMatrix();
        w = (r * body.inverse_inertia * r.transpose() * body.angular_momentum0).norm();
      } else {
        for (int i = 0; i < 4; ++i) {
          x[i] = m.masses[body.first_mass + i].position;
          v[i] = m.masses[body.first_mass + i].velocity;
        }
        w = fit_angular_velocity(x, v).norm();
      }
      const double f_peak =
          body.mass * (s.load_factor * g + w * w * body.size) + applied + 1e-9 * body.mass;
      const double k = f_peak / (s.strain_budget * body.min_edge);
      for (auto& c : m.connections) {
        if (c.kind != ConnectionClass::kInternal || c.a.kind != NodeRef::Kind::kMass) continue;
        const Mass& ma = m.masses[c.a.index];
        if (ma.body == static_cast<int>(b) || ma.dummy_of == static_cast<int>(b)) c.stiffness = k;
      }
      out.internal_min = std::min(out.internal_min, k);
      out.internal_max = std::max(out.internal_max, k);
    }
    if (m.bodies.empty()) out.internal_min = 0.0;
  }
  if (s.contact_auto) {
    out.contact = s.load_factor * m.total_mass() * std::max(g, 1e-9) / s.penetration_budget;
    for (auto& surf : m.surfaces) surf.stiffness = out.contact;
  }
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "strain budget %.3g, penetration budget %.3g m, load factor %.3g body weights",
                s.strain_budget, s.penetration_budget, s.load_factor);
  out.note = buf;
  return out;
}

}  // namespace pronk::pseudorigid
