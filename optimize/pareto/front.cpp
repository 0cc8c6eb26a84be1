#include "optimize/pareto/front.hpp"

#include <pagmo/utils/hypervolume.hpp>
#include <pagmo/utils/multi_objective.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pronk::optimize::pareto {

namespace {

bool finite(const Objectives& f) {
  return std::all_of(f.begin(), f.end(), [](double v) { return std::isfinite(v); });
}

// Same length everywhere and no NaN, or std::invalid_argument naming the point.
void check_points(const std::vector<Objectives>& points, const char* who) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].size() != points[0].size())
      throw std::invalid_argument(std::string(who) + ": point " + std::to_string(i) + " has " +
                                  std::to_string(points[i].size()) + " objectives, point 0 has " +
                                  std::to_string(points[0].size()));
    for (double v : points[i])
      if (std::isnan(v))
        throw std::invalid_argument(std::string(who) + ": point " + std::to_string(i) +
                                    " has a NaN objective");
  }
}

// Indices of the points whose objectives are all finite.
std::vector<std::size_t> finite_indices(const std::vector<Objectives>& points) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (finite(points[i])) out.push_back(i);
  return out;
}

std::vector<Objectives> pick(const std::vector<Objectives>& points,
                             const std::vector<std::size_t>& idx) {
  std::vector<Objectives> out;
  out.reserve(idx.size());
  for (std::size_t i : idx) out.push_back(points[i]);
  return out;
}

// The plane n . f = 1 through the normalized extreme points, or n = (1, ..., 1) when they do
// not fix one (see knee() in front.hpp).
Eigen::VectorXd extreme_plane(const std::vector<Objectives>& g) {
  const std::size_t m = g[0].size();
  Eigen::MatrixXd e(m, m);
  for (std::size_t j = 0; j < m; ++j) {
    std::size_t best = 0;
    double best_sum = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double sum = std::accumulate(g[i].begin(), g[i].end(), 0.0);
      if (i == 0 || g[i][j] < g[best][j] || (g[i][j] == g[best][j] && sum < best_sum)) {
        best = i;
        best_sum = sum;
      }
    }
    for (std::size_t k = 0; k < m; ++k) e(static_cast<long>(j), static_cast<long>(k)) = g[best][k];
  }
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(static_cast<long>(m));
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(e);
  if (lu.rank() == static_cast<long>(m)) {
    const Eigen::VectorXd n = lu.solve(ones);
    // A plane that does not separate the ideal (the origin) from the extremes is no use.
    if (n.allFinite() && (n.array() > 0.0).all()) return n;
  }
  return ones;
}

}  // namespace

std::vector<std::size_t> non_dominated(const std::vector<Objectives>& points) {
  check_points(points, "non_dominated");
  std::vector<std::size_t> front;
  extend_front(points, 0, &front);
  return front;
}

std::vector<std::vector<std::size_t>> non_dominated_sort(const std::vector<Objectives>& points) {
  check_points(points, "non_dominated_sort");
  if (points.empty()) return {};
  if (points.size() == 1) return {{0}};
  auto fronts = std::get<0>(pagmo::fast_non_dominated_sorting(points));
  for (auto& f : fronts) std::sort(f.begin(), f.end());
  std::vector<std::vector<std::size_t>> out;
  for (const auto& f : fronts)
    if (!f.empty()) out.emplace_back(f.begin(), f.end());
  return out;
}

void extend_front(const std::vector<Objectives>& points, std::size_t first_new,
                  std::vector<std::size_t>* front) {
  check_points(points, "extend_front");
  for (std::size_t i = first_new; i < points.size(); ++i) {
    const Objectives& p = points[i];
    const bool covered = std::any_of(front->begin(), front->end(), [&](std::size_t k) {
      return points[k] == p || pagmo::pareto_dominance(points[k], p);
    });
    if (covered) continue;
    front->erase(
        std::remove_if(front->begin(), front->end(),
                       [&](std::size_t k) { return pagmo::pareto_dominance(p, points[k]); }),
        front->end());
    front->push_back(i);  // i exceeds every index already in: the order stays ascending
  }
}

double hypervolume(const std::vector<Objectives>& points, const Objectives& reference) {
  check_points(points, "hypervolume");
  for (double r : reference)
    if (std::isnan(r)) throw std::invalid_argument("hypervolume: the reference point has a NaN");
  if (!points.empty() && points[0].size() != reference.size())
    throw std::invalid_argument("hypervolume: the reference point has " +
                                std::to_string(reference.size()) + " objectives, the points " +
                                std::to_string(points[0].size()));
  std::vector<Objectives> inside;
  for (const Objectives& p : points) {
    bool strictly = true;
    for (std::size_t j = 0; j < p.size(); ++j) strictly = strictly && p[j] < reference[j];
    if (strictly) inside.push_back(p);
  }
  if (inside.empty()) return 0.0;
  return pagmo::hypervolume(inside, true).compute(reference);
}

Objectives reference_point(const std::vector<Objectives>& points) {
  check_points(points, "reference_point");
  const std::vector<Objectives> ok = pick(points, finite_indices(points));
  if (ok.empty()) throw std::invalid_argument("reference_point: no point has finite objectives");
  const std::vector<Objectives> front = pick(ok, non_dominated(ok));
  Objectives lo = front[0], hi = front[0];
  for (const Objectives& f : front) {
    for (std::size_t j = 0; j < f.size(); ++j) {
      lo[j] = std::min(lo[j], f[j]);
      hi[j] = std::max(hi[j], f[j]);
    }
  }
  Objectives r(hi.size());
  for (std::size_t j = 0; j < r.size(); ++j) {
    const double range = hi[j] - lo[j];
    r[j] = hi[j] + (range > 0.0 ? 0.1 * range : 0.1 * std::max(std::abs(hi[j]), 1.0));
  }
  return r;
}

long knee(const std::vector<Objectives>& points) {
  check_points(points, "knee");
  const std::vector<std::size_t> ok = finite_indices(points);
  const std::vector<Objectives> finite_points = pick(points, ok);
  std::vector<std::size_t> front = non_dominated(finite_points);
  if (front.empty()) return -1;
  if (front.size() == 1) return static_cast<long>(ok[front[0]]);
  // Normalize by the front's ideal and nadir.
  std::vector<Objectives> g = pick(finite_points, front);
  const std::size_t m = g[0].size();
  for (std::size_t j = 0; j < m; ++j) {
    double lo = g[0][j], hi = g[0][j];
    for (const Objectives& f : g) {
      lo = std::min(lo, f[j]);
      hi = std::max(hi, f[j]);
    }
    const double scale = hi > lo ? hi - lo : 1.0;
    for (Objectives& f : g) f[j] = (f[j] - lo) / scale;
  }
  const Eigen::VectorXd n = extreme_plane(g);
  std::size_t best = 0;
  double best_d = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const Eigen::Map<const Eigen::VectorXd> f(g[i].data(), static_cast<long>(m));
    const double d = (1.0 - n.dot(f)) / n.norm();
    if (i == 0 || d > best_d) {
      best = i;
      best_d = d;
    }
  }
  return static_cast<long>(ok[front[best]]);
}

}  // namespace pronk::optimize::pareto
