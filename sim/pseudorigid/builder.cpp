#include "sim/pseudorigid/builder.hpp"

#include <algorithm>

#include <Eigen/LU>

#include "sim/pseudorigid/rigid_body.hpp"

namespace pronk::pseudorigid {

NodeRef add_mass(Mechanism& m, const std::string& name, double mass,
                 const Eigen::Vector3d& position, const Eigen::Vector3d& velocity) {
  Mass ms;
  ms.name = name;
  ms.mass = mass;
  ms.position = position;
  ms.velocity = velocity;
  m.masses.push_back(ms);
  return NodeRef{NodeRef::Kind::kMass, static_cast<int>(m.masses.size()) - 1};
}

int add_body(Mechanism& m, const BodySpec& spec, std::string* error) {
  Body b;
  if (!construct_body(spec.mass, spec.inertia, &b.local, error)) return -1;
  b.name = spec.name;
  b.mass = spec.mass;
  b.inertia = spec.inertia;
  b.first_mass = static_cast<int>(m.masses.size());
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  b.size = 0.0;
  for (const auto& r : b.local) {
    g += r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
    b.size = std::max(b.size, r.norm());
  }
  b.geometric_inverse = g.inverse();
  const int index = static_cast<int>(m.bodies.size());
  b.min_edge = 1e300;
  for (int i = 0; i < 4; ++i) {
    for (int k = i + 1; k < 4; ++k)
      b.min_edge = std::min(b.min_edge, (b.local[i] - b.local[k]).norm());
  }
  if (spec.rigid) {
    // One mass for the translation; the rotation's states follow all masses' (model.hpp).
    b.rigid = true;
    b.inverse_inertia = spec.inertia.inverse();
    principal_axes(spec.inertia, &b.principal_moments, &b.principal_axes);
    b.attitude0 = Eigen::Quaterniond(spec.attitude).normalized();
    b.angular_momentum0 = spec.attitude * spec.inertia * spec.attitude.transpose() * spec.omega;
    Mass ms;
    ms.name = spec.name;
    ms.mass = spec.mass;
    ms.position = spec.com;
    ms.velocity = spec.velocity;
    ms.body = index;
    m.masses.push_back(ms);
    m.bodies.push_back(b);
    return index;
  }
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d arm = spec.attitude * b.local[i];
    Mass ms;
    ms.name = spec.name + "." + std::to_string(i);
    ms.mass = 0.25 * spec.mass;
    ms.position = spec.com + arm;
    ms.velocity = spec.velocity + spec.omega.cross(arm);
    ms.body = index;
    m.masses.push_back(ms);
  }
  for (int i = 0; i < 4; ++i) {
    for (int k = i + 1; k < 4; ++k) {
      Connection c;
      c.name = spec.name + ".internal" + std::to_string(i) + std::to_string(k);
      c.a = NodeRef{NodeRef::Kind::kMass, b.first_mass + i};
      c.b = NodeRef{NodeRef::Kind::kMass, b.first_mass + k};
      c.kind = ConnectionClass::kInternal;
      c.stiffness = spec.internal_stiffness;
      c.damping = spec.internal_damping;
      c.rest_length = (b.local[i] - b.local[k]).norm();
      m.connections.push_back(c);
    }
  }
  m.bodies.push_back(b);
  return index;
}

NodeRef add_ghost_point(Mechanism& m, int body, const std::string& name,
                        const Eigen::Vector3d& local) {
  GhostPoint g;
  g.name = name;
  g.body = body;
  g.local = local;
  prepare_ghost_point(m.bodies[body].local, &g);
  m.ghost_points.push_back(g);
  return NodeRef{NodeRef::Kind::kGhost, static_cast<int>(m.ghost_points.size()) - 1};
}

int add_reference_point(Mechanism& m, int body, const std::string& name,
                        const Eigen::Vector3d& local) {
  m.reference_points.push_back(ReferencePoint{name, body, local});
  return static_cast<int>(m.reference_points.size()) - 1;
}

NodeRef add_dummy_mass(Mechanism& m, int body, const std::string& name,
                       const Eigen::Vector3d& local, double dummy_ratio, double stiffness,
                       double damping) {
  const Body& b = m.bodies[body];
  // Initial placement and velocity follow the body's masses (rigid motion).
  GhostPoint probe;
  probe.local = local;
  prepare_ghost_point(b.local, &probe);
  Eigen::Vector3d x = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    x += probe.weights[i] * m.masses[b.first_mass + i].position;
    v += probe.weights[i] * m.masses[b.first_mass + i].velocity;
  }
  const NodeRef n = add_mass(m, name, dummy_ratio * b.mass, x, v);
  m.masses.back().dummy_of = body;
  for (int i = 0; i < 4; ++i) {
    Connection c;
    c.name = name + ".tie" + std::to_string(i);
    c.a = n;
    c.b = NodeRef{NodeRef::Kind::kMass, m.bodies[body].first_mass + i};
    c.kind = ConnectionClass::kInternal;
    c.stiffness = stiffness;
    c.damping = damping;
    c.rest_length = (local - m.bodies[body].local[i]).norm();
    m.connections.push_back(c);
  }
  return n;
}

NodeRef add_anchor(Mechanism& m, const std::string& name, const Eigen::Vector3d& position) {
  m.anchors.push_back(Anchor{name, position});
  return NodeRef{NodeRef::Kind::kAnchor, static_cast<int>(m.anchors.size()) - 1};
}

void set_internal_stiffness(Mechanism& m, double k) {
  for (Connection& c : m.connections) {
    if (c.kind == ConnectionClass::kInternal) c.stiffness = k;
  }
}

}  // namespace pronk::pseudorigid
