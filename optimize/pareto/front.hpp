// Pareto-front numerics on objective vectors, every objective minimized: which points are
// non-dominated, non-dominated sorting, the hypervolume of a set, a run's reference point and
// the knee of a front. Pure functions of the vectors (no physics, no pagmo in this header);
// dominance, sorting and hypervolume are pagmo's (<pagmo/utils/multi_objective.hpp>,
// <pagmo/utils/hypervolume.hpp>), this layer adds the deterministic order of the answers.
//
// Dominance: a dominates b when a_j <= b_j for every j and a_j < b_j for some j. Two equal
// vectors do not dominate each other; the filters below keep the first of them (lowest index).
// NaN objective values are rejected (std::invalid_argument); +inf is an ordinary large value.
#pragma once

#include <cstddef>
#include <vector>

namespace pronk::optimize::pareto {

using Objectives = std::vector<double>;  ///< one point's objective values

/// Indices of the non-dominated points of `points`, ascending. Of several points with equal
/// objective vectors only the first is kept. An empty set gives an empty answer.
std::vector<std::size_t> non_dominated(const std::vector<Objectives>& points);

/// The non-dominated fronts of `points` (pagmo's fast non-dominated sorting, Deb et al.
/// 2002): front 0 is non_dominated() plus the duplicates it left out, front 1 what only front
/// 0 dominates, and so on. Each front's indices ascending; every index appears once.
std::vector<std::vector<std::size_t>> non_dominated_sort(const std::vector<Objectives>& points);

/// Adds points[first_new ..] to `front` (indices of a non-dominated subset of
/// points[0 .. first_new), ascending) in index order: a point enters unless a front member
/// dominates or equals it, and pushes out the members it dominates. The result is
/// non_dominated() of points[0 ..] as long as `front` was that of points[0 .. first_new).
/// Costs O(new points x front size), for archives of every evaluation of a run.
void extend_front(const std::vector<Objectives>& points, std::size_t first_new,
                  std::vector<std::size_t>* front);

/// The volume of objective space that the points dominate and that is bounded by
/// `reference` (pagmo::hypervolume: Kung/sweep in 2-D, Beume et al. in 3-D, WFG beyond).
/// Points that do not strictly dominate the reference (f_j < r_j for every j) add nothing
/// and are left out; an empty set (or none left) gives 0. Throws std::invalid_argument for
/// a reference of another length or a NaN.
double hypervolume(const std::vector<Objectives>& points, const Objectives& reference);

/// The reference point of a run: the nadir of the non-dominated points among `points` (the
/// first generation), pushed out by 10 % of the set's range per objective:
///   r_j = nadir_j + 0.1 (nadir_j - ideal_j),
/// or by 0.1 max(|nadir_j|, 1) when the range is 0 (a single point). Points with a
/// non-finite objective are left out. Throws std::invalid_argument when no point is finite.
Objectives reference_point(const std::vector<Objectives>& points);

/// The knee of the non-dominated points among `points`, as an index into `points` (-1 for an
/// empty set). Rule: objectives are normalized to [0, 1] by the front's ideal and nadir
/// (an objective with no range is left as f_j - ideal_j); the extreme point of objective j is
/// the front point with the least f_j (ties: least sum of the normalized objectives, then
/// lowest index); the hyperplane through the m extreme points (in 2-D the line through the two
/// ends, which normalize to (0, 1) and (1, 0)) is written n . f = 1, or sum_j f_j = 1 when the
/// extremes do not fix one plane (coincident or affinely dependent, or a plane through the
/// origin). The knee is the point with the largest signed distance (1 - n . f) / |n| towards
/// the ideal: on a convex front the point bulging farthest from the plane of the extremes;
/// on a concave front (every point beyond the plane) an extreme point, at distance 0. Ties:
/// lowest index. Points with a non-finite objective are left out.
long knee(const std::vector<Objectives>& points);

}  // namespace pronk::optimize::pareto
