#include "sim/pseudorigid/scene_probe.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sim/pseudorigid/attitude.hpp"
#include "sim/pseudorigid/stability.hpp"

namespace pronk::pseudorigid {

namespace {

/// One spring-like element: its 3x3 stiffness [N/m] on the relative displacement
/// sum_i c_i x_i of the masses it moves (weights c, mass indices).
struct Element {
  Eigen::Matrix3d stiffness;
  std::vector<std::pair<int, double>> weights;
};

/// Initial world positions and body rotations the probe reads directions from.
class Geometry {
 public:
  explicit Geometry(const Mechanism& m) : m_(m) {
    rotation_.reserve(m.bodies.size());
    for (const Body& b : m.bodies) rotation_.push_back(body_rotation(b));
  }

  /// World position of node n at t = 0 [m].
  Eigen::Vector3d position(const NodeRef& n) const {
    if (n.kind == NodeRef::Kind::kAnchor) return m_.anchors[static_cast<size_t>(n.index)].position;
    if (n.kind == NodeRef::Kind::kMass) return m_.masses[static_cast<size_t>(n.index)].position;
    const GhostPoint& g = m_.ghost_points[static_cast<size_t>(n.index)];
    const Body& b = m_.bodies[static_cast<size_t>(g.body)];
    return com(b) + rotation_[static_cast<size_t>(g.body)] * g.local;
  }

  /// Body b's rotation (body to world) at t = 0.
  const Eigen::Matrix3d& rotation(int b) const { return rotation_[static_cast<size_t>(b)]; }

  /// Appends the (mass, weight) pairs through which node n moves (anchors: none); a rigid
  /// body's point counts on its CoM mass with the weight sqrt(1 + M |r|^2 / I_min), as in
  /// max_frequency_bound (stability.cpp).
  void weights(const NodeRef& n, double sign, std::vector<std::pair<int, double>>& out) const {
    if (n.kind == NodeRef::Kind::kMass) {
      out.emplace_back(n.index, sign);
    } else if (n.kind == NodeRef::Kind::kGhost) {
      const GhostPoint& g = m_.ghost_points[static_cast<size_t>(n.index)];
      const Body& b = m_.bodies[static_cast<size_t>(g.body)];
      if (b.rigid) {
        const double w =
            std::sqrt(1.0 + b.mass * g.local.squaredNorm() / b.principal_moments.minCoeff());
        out.emplace_back(b.first_mass, sign * w);
        return;
      }
      for (int k = 0; k < 4; ++k) out.emplace_back(b.first_mass + k, sign * g.weights[k]);
    }
  }

 private:
  Eigen::Vector3d com(const Body& b) const {
    if (b.rigid) return m_.masses[static_cast<size_t>(b.first_mass)].position;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += m_.masses[static_cast<size_t>(b.first_mass + k)].position;
    return c / 4.0;
  }

  Eigen::Matrix3d body_rotation(const Body& b) const {
    if (b.rigid) return b.attitude0.normalized().toRotationMatrix();
    std::array<Eigen::Vector3d, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = m_.masses[static_cast<size_t>(b.first_mass + k)].position;
    return fit_attitude(x, b.local).rotation;
  }

  const Mechanism& m_;
  std::vector<Eigen::Matrix3d> rotation_;
};

/// A connection's stiffness along and across its direction at t = 0: k d d^T plus the
/// tension's k (1 - l0/l) across (a zero-rest-length spring is isotropic); k 1 at zero length.
Eigen::Matrix3d connection_stiffness(const Connection& c, const Eigen::Vector3d& d) {
  const double l = d.norm();
  if (!(l > 1e-12)) return c.stiffness * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d u = d / l;
  const Eigen::Matrix3d along = u * u.transpose();
  const double across = std::max(0.0, c.stiffness * (1.0 - c.rest_length / l));
  return c.stiffness * along + across * (Eigen::Matrix3d::Identity() - along);
}

/// A surface's stiffness on one of its nodes, engaged: plane k n n^T, line k (1 - d d^T),
/// point k 1 (directions turned with an attached surface's body).
Eigen::Matrix3d surface_stiffness(const Surface& s, const Geometry& geo) {
  Eigen::Vector3d d = s.direction.normalized();
  if (s.body >= 0) d = geo.rotation(s.body) * d;
  const Eigen::Matrix3d dd = d * d.transpose();
  switch (s.type) {
    case SurfaceType::kPlane:
      return s.stiffness * dd;
    case SurfaceType::kLine:
      return s.stiffness * (Eigen::Matrix3d::Identity() - dd);
    case SurfaceType::kPoint:
      break;
  }
  return s.stiffness * Eigen::Matrix3d::Identity();
}

std::vector<Element> elements(const Mechanism& m) {
  const Geometry geo(m);
  std::vector<Element> out;
  for (const Connection& c : m.connections) {
    if (!(c.stiffness > 0.0)) continue;
    Element e;
    e.stiffness = connection_stiffness(c, geo.position(c.a) - geo.position(c.b));
    geo.weights(c.a, 1.0, e.weights);
    geo.weights(c.b, -1.0, e.weights);
    out.push_back(std::move(e));
  }
  for (const Surface& s : m.surfaces) {
    if (!(s.stiffness > 0.0)) continue;
    const Eigen::Matrix3d k = surface_stiffness(s, geo);
    for (const NodeRef& n : s.nodes) {
      Element e;
      e.stiffness = k;
      geo.weights(n, 1.0, e.weights);
      if (s.body >= 0) geo.weights(NodeRef{NodeRef::Kind::kGhost, s.ghost}, -1.0, e.weights);
      out.push_back(std::move(e));
    }
  }
  return out;
}

/// y = M^-1/2 K M^-1/2 x over the elements (x, y: 3 per mass).
void apply_stiffness(const std::vector<Element>& elements, const std::vector<double>& inv_sqrt_m,
                     const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  y.setZero();
  for (const Element& e : elements) {
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    for (const auto& [i, w] : e.weights) u += w * inv_sqrt_m[i] * x.segment<3>(3 * i);
    const Eigen::Vector3d f = e.stiffness * u;
    for (const auto& [i, w] : e.weights) y.segment<3>(3 * i) += w * inv_sqrt_m[i] * f;
  }
}

/// Largest eigenvalue of the symmetric positive semi-definite M^-1/2 K M^-1/2 by power
/// iteration from a fixed start vector: the Rayleigh quotient after convergence to 1e-8
/// (at most 500 iterations).
double largest_eigenvalue(const std::vector<Element>& elements, const Mechanism& m) {
  const size_t n = m.masses.size();
  std::vector<double> inv_sqrt_m(n);
  for (size_t i = 0; i < n; ++i) inv_sqrt_m[i] = 1.0 / std::sqrt(m.masses[i].mass);
  Eigen::VectorXd x(static_cast<Eigen::Index>(3 * n)), y(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    x[i] = 1.0 + 0.37 * static_cast<double>((i * 7919) % 23) / 23.0;  // no symmetry to hide in
  }
  x.normalize();
  double lambda = 0.0;
  for (int it = 0; it < 500; ++it) {
    apply_stiffness(elements, inv_sqrt_m, x, y);
    const double next = x.dot(y);
    const double norm = y.norm();
    if (!(norm > 0.0)) return 0.0;
    x = y / norm;
    if (std::abs(next - lambda) <= 1e-8 * next) return next;
    lambda = next;
  }
  return lambda;
}

bool is_dissipative(const Connection& c) {
  return c.kind != ConnectionClass::kActuator &&
         (c.damping > 0.0 || c.friction > 0.0 || c.drag > 0.0);
}

/// Mirrors MechanismSystem's rule (system.cpp): under min_norm, a dissipative element on a
/// ghost point keeps Verlet's dissipation in the kicks.
bool has_dissipation_split(const Mechanism& m) {
  if (m.simulation.ghost_transfer != GhostTransfer::kMinNorm) return true;
  auto ghost = [](const NodeRef& n) { return n.kind == NodeRef::Kind::kGhost; };
  for (const Connection& c : m.connections) {
    if (is_dissipative(c) && (ghost(c.a) || ghost(c.b))) return false;
  }
  for (const Surface& s : m.surfaces) {
    if (s.body >= 0 || (s.damping == 0.0 && s.friction == 0.0)) continue;
    for (const NodeRef& n : s.nodes) {
      if (ghost(n)) return false;
    }
  }
  return true;
}

/// Inverse effective mass of node n [1/kg]: sum w_i^2 / m_i over the masses it moves.
double inverse_mass(const Geometry& geo, const Mechanism& m, const NodeRef& n) {
  std::vector<std::pair<int, double>> w;
  geo.weights(n, 1.0, w);
  double inv = 0.0;
  for (const auto& [i, c] : w) inv += c * c / m.masses[static_cast<size_t>(i)].mass;
  return inv;
}

/// The highest sqrt(k / m) of a node on an elastic one-sided plane (damping ratio < 0.1).
double elastic_contact_frequency(const Mechanism& m) {
  const Geometry geo(m);
  double w2 = 0.0;
  for (const Surface& s : m.surfaces) {
    if (s.type != SurfaceType::kPlane || s.bilateral || !(s.stiffness > 0.0)) continue;
    for (const NodeRef& n : s.nodes) {
      const double inv = inverse_mass(geo, m, n);
      if (!(inv > 0.0)) continue;
      const double zeta = s.damping / (2.0 * std::sqrt(s.stiffness / inv));
      if (zeta < 0.1) w2 = std::max(w2, s.stiffness * inv);
    }
  }
  return std::sqrt(w2);
}

}  // namespace

SceneProbe probe_scene(const Mechanism& m) {
  SceneProbe p;
  const std::vector<Element> springs = elements(m);
  p.springs = static_cast<int>(springs.size());
  p.omega_max = std::sqrt(std::max(0.0, largest_eigenvalue(springs, m)));
  p.omega_bound = max_frequency_bound(m);
  p.omega_elastic_contact = elastic_contact_frequency(m);
  p.min_mass = m.masses.empty() ? 0.0 : m.masses.front().mass;
  for (const Mass& x : m.masses) p.min_mass = std::min(p.min_mass, x.mass);
  for (const Connection& c : m.connections) p.dissipation = p.dissipation || is_dissipative(c);
  for (const Surface& s : m.surfaces) {
    p.dissipation = p.dissipation || s.damping > 0.0 || s.friction > 0.0;
    p.contact = p.contact || (s.type == SurfaceType::kPlane && !s.bilateral && s.stiffness > 0.0);
  }
  p.dissipation_split = has_dissipation_split(m);
  return p;
}

}  // namespace pronk::pseudorigid
