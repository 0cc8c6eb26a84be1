#include "sim/pseudorigid/model.hpp"

#include <cmath>
#include <cstdio>

namespace pronk::pseudorigid {
namespace {

bool fail(std::string* error, const std::string& what) {
  if (error) *error = what;
  return false;
}

}  // namespace

bool SimulationOptions::validate(std::string* error) const {
  auto bad = [&](const char* field, double v, const char* rule) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: %g: %s", field, v, rule);
    return fail(error, buf);
  };
  if (!(t_end > 0.0) || !std::isfinite(t_end)) return bad("t_end", t_end, "must be > 0 and finite");
  if (!(output_interval > 0.0) || !std::isfinite(output_interval)) {
    return bad("output_interval", output_interval, "must be > 0 and finite");
  }
  if (!(energy_blowup_factor > 0.0)) {
    return bad("energy_blowup_factor", energy_blowup_factor, "must be > 0");
  }
  if (!(zero_length_epsilon > 0.0)) {
    return bad("zero_length_epsilon", zero_length_epsilon, "must be > 0");
  }
  if (!(energy_tol >= 0.0) || !(energy_tol <= 0.5)) {
    return bad("energy_tol", energy_tol, "must be >= 0 (0: off) and <= 0.5");
  }
  if (!(strain_budget > 0.0)) return bad("strain_budget", strain_budget, "must be > 0");
  if (!(penetration_budget > 0.0)) {
    return bad("penetration_budget", penetration_budget, "must be > 0");
  }
  std::string e;
  if (!solver.validate(&e)) return fail(error, "solver." + e);
  if (error) error->clear();
  return true;
}

double Mechanism::total_mass() const {
  double s = 0.0;
  for (const Mass& m : masses) s += m.mass;
  return s;
}

int Mechanism::rigid_bodies() const {
  int n = 0;
  for (const Body& b : bodies) n += b.rigid ? 1 : 0;
  return n;
}

int Mechanism::rotation_state(int b) const {
  if (!bodies[static_cast<size_t>(b)].rigid) return -1;
  int k = 0;
  for (int i = 0; i < b; ++i) k += bodies[static_cast<size_t>(i)].rigid ? 1 : 0;
  return 6 * static_cast<int>(masses.size()) + 7 * k;
}

Eigen::VectorXd Mechanism::initial_state() const {
  Eigen::VectorXd y(dimension());
  for (size_t j = 0; j < masses.size(); ++j) {
    y.segment<3>(6 * j) = masses[j].position;
    y.segment<3>(6 * j + 3) = masses[j].mass * masses[j].velocity;
  }
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    const int r = rotation_state(b);
    if (r < 0) continue;
    const Eigen::Quaterniond& q = bodies[static_cast<size_t>(b)].attitude0;
    y.segment<4>(r) << q.w(), q.x(), q.y(), q.z();
    y.segment<3>(r + 4) = bodies[static_cast<size_t>(b)].angular_momentum0;
  }
  return y;
}

std::string Mechanism::node_name(const NodeRef& n) const {
  switch (n.kind) {
    case NodeRef::Kind::kMass:
      return masses[n.index].name;
    case NodeRef::Kind::kGhost:
      return ghost_points[n.index].name;
    case NodeRef::Kind::kAnchor:
      return anchors[n.index].name;
  }
  return "?";
}

bool Mechanism::validate(std::string* error) const {
  auto node_ok = [&](const NodeRef& n) {
    switch (n.kind) {
      case NodeRef::Kind::kMass:
        return n.index >= 0 && n.index < static_cast<int>(masses.size());
      case NodeRef::Kind::kGhost:
        return n.index >= 0 && n.index < static_cast<int>(ghost_points.size());
      case NodeRef::Kind::kAnchor:
        return n.index >= 0 && n.index < static_cast<int>(anchors.size());
    }
    return false;
  };
  if (masses.empty()) return fail(error, "mechanism has no masses");
  for (const Mass& m : masses) {
    if (!(m.mass > 0.0) || !std::isfinite(m.mass))
      return fail(error, m.name + ": mass must be > 0");
  }
  for (const Connection& c : connections) {
    if (!node_ok(c.a) || !node_ok(c.b)) return fail(error, c.name + ": node out of range");
    if (c.a == c.b) return fail(error, c.name + ": connects a node to itself");
    if (c.stiffness < 0 || c.damping < 0 || c.friction < 0 || c.drag < 0 || c.rest_length < 0 ||
        c.force_limit < 0) {
      return fail(error, c.name + ": coefficients must be >= 0");
    }
  }
  for (const Surface& s : surfaces) {
    for (const NodeRef& n : s.nodes) {
      if (!node_ok(n)) return fail(error, s.name + ": node out of range");
    }
    if (std::abs(s.direction.norm() - 1.0) > 1e-9)
      return fail(error, s.name + ": direction not unit");
    if (s.body >= static_cast<int>(bodies.size()))
      return fail(error, s.name + ": body out of range");
  }
  for (const ImpulseActuator& a : impulse_actuators) {
    if (!(a.force > 0.0) || !(a.impulse >= 0.0)) {
      return fail(error, a.name + ": force must be > 0 and impulse >= 0");
    }
  }
  return simulation.validate(error);
}

}  // namespace pronk::pseudorigid
