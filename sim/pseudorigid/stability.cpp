#include "sim/pseudorigid/stability.hpp"

#include <cmath>
#include <utility>
#include <vector>

namespace pronk::pseudorigid {

namespace {

/// Appends the (mass, weight) pairs through which node n moves (anchors: none).
void weights(const Mechanism& m, const NodeRef& n, double sign,
             std::vector<std::pair<int, double>>& out) {
  if (n.kind == NodeRef::Kind::kMass) {
    out.emplace_back(n.index, sign);
  } else if (n.kind == NodeRef::Kind::kGhost) {
    const GhostPoint& g = m.ghost_points[static_cast<size_t>(n.index)];
    const Body& b = m.bodies[static_cast<size_t>(g.body)];
    const int first = b.first_mass;
    if (b.rigid) {
      // A rigid body's point moves with its CoM mass M and its rotation: its inverse effective
      // mass is at most 1/M + |r|^2 / I_min = w^2 / M, w = sqrt(1 + M |r|^2 / I_min).
      const double w =
          std::sqrt(1.0 + b.mass * g.local.squaredNorm() / b.principal_moments.minCoeff());
      out.emplace_back(first, sign * w);
      return;
    }
    for (int k = 0; k < 4; ++k) out.emplace_back(first + k, sign * g.weights[k]);
  }
}

/// Adds one element of stiffness k on the weights c to the Gershgorin row sums.
void add_element(double k, const std::vector<std::pair<int, double>>& c, std::vector<double>& row) {
  double sum = 0.0;
  for (const auto& [mass, w] : c) sum += std::abs(w);
  for (const auto& [mass, w] : c) row[static_cast<size_t>(mass)] += k * std::abs(w) * sum;
}

}  // namespace

double max_frequency_bound(const Mechanism& m) {
  std::vector<double> row(m.masses.size(), 0.0);
  std::vector<std::pair<int, double>> c;
  for (const Connection& e : m.connections) {
    if (!(e.stiffness > 0.0)) continue;
    c.clear();
    weights(m, e.a, 1.0, c);
    weights(m, e.b, -1.0, c);
    add_element(e.stiffness, c, row);
  }
  for (const Surface& s : m.surfaces) {
    if (!(s.stiffness > 0.0)) continue;
    for (const NodeRef& n : s.nodes) {
      c.clear();
      weights(m, n, 1.0, c);
      if (s.body >= 0) weights(m, NodeRef{NodeRef::Kind::kGhost, s.ghost}, -1.0, c);
      add_element(s.stiffness, c, row);
    }
  }
  double w2 = 0.0;
  for (size_t i = 0; i < row.size(); ++i) w2 = std::max(w2, row[i] / m.masses[i].mass);
  return std::sqrt(w2);
}

}  // namespace pronk::pseudorigid
