// Impulse allocation (Ridgely 2001, §2.3, 2.5.3): per-leg linear impulses p_i applied at
// the hips r_i (body frame, relative to the CoM) that produce a requested net
// linear impulse P and angular impulse H about the CoM.
//
// ---------------------------------------------------------------------------
// Model. Legs push with p_i = (p_x, 0, p_z) in the body frame (no lateral
// component). With r = (r_x, r_y, r_z):
//
//   r × p = (r_y p_z - r_z p_y,  r_z p_x - r_x p_z,  r_x p_y - r_y p_x)
//         = (r_y p_z,            r_z p_x - r_x p_z,  -r_y p_x)          (p_y = 0)
//
// so  P_x = Σ p_x,   P_y = 0,   P_z = Σ p_z,
//     H_x = Σ r_y p_z,   H_y = Σ (r_z p_x - r_x p_z),   H_z = -Σ r_y p_x.
//
// P_y can never be produced; it is dropped (and reported) and the remaining
// five components b = (P_x, P_z, H_x, H_y, H_z) are allocated.
//
// ---------------------------------------------------------------------------
// kMinimumNorm. Unknowns x = (p_x,1, p_z,1, ..., p_x,N, p_z,N) over the N active
// legs; A x = b with the columns of A for leg i
//
//   p_x,i -> (1, 0, 0,     r_z,i, -r_y,i)ᵀ
//   p_z,i -> (0, 1, r_y,i, -r_x,i, 0     )ᵀ
//
// x = A⁺ b (= Aᵀ(AAᵀ)⁻¹ b when A has full row rank), computed with a complete
// orthogonal decomposition (column-pivoted QR with pivots below
// kRankThreshold × the largest pivot treated as zero), which gives the
// minimum-norm least-squares solution for rank-deficient layouts too. For ≤ 8
// active legs it works on fixed-capacity matrices (see solve_minimum_norm).
//
// When is A (5 × 2N) rank deficient? A left null vector w = (w1..w5) needs, for
// every active hip, f(r) = w1 + w4 r_z - w5 r_y = 0 and g(r) = w2 + w3 r_y - w4 r_x = 0.
// Each nonzero affine function vanishes on a plane (f's normal ⟂ x, g's ⟂ z),
// so the hips must lie on a line (intersection of two distinct planes), or on
// a single plane that is simultaneously an f- and a g-plane: only r_y = const
// (then H_x = y0 P_z and H_z = -y0 P_x are tied to P). Hence: rank 5 ⇔ at least
// three non-collinear active hips that do not all share the same r_y.
// Collinear hips (incl. any 2 legs, e.g. a trot diagonal pair) can never
// produce a moment about the leg line relative to that line:
// d · (H - r_1 × P) = 0 for any forces applied on the line.
//
// Leg limits (minimum-norm scheme only, per the header): if max |p_i| exceeds
// max_leg_impulse, all impulses are scaled by the same factor so the largest
// equals the limit (the direction of (P, H) is kept, its magnitude is not).
//
// ---------------------------------------------------------------------------
// kSeed (Ridgely 2001, eq. 2.7-2.8, corrected). Equal share p_i⁰ = (P_x/N, 0, P_z/N),
// then per-leg additions δp_i = (c r_y,i, 0, a r_x,i + b r_y,i).
//
// The equal shares produce moment Σ r_i × p⁰ = (Σ r_i) × p⁰; the additions must
// produce the residual H' = H - (Σ r_i) × p⁰. The seed omitted this term: for a
// layout with Σ r_x = Σ r_y = 0 but a common hip height r_z = z0 ≠ 0 (hips
// below the CoM), (Σ r) × p⁰ = (0, N z0 P_x / N, 0) = (0, z0 P_x, 0), which the
// seed neglected (its H_y would be off by z0 P_x).
//
// Moments of the additions (using the cross product above, with p_y = 0):
//   x:  Σ r_y (a r_x + b r_y)               = a Σ r_x r_y + b Σ r_y²
//   y:  Σ (r_z c r_y - r_x (a r_x + b r_y)) = c Σ r_y r_z - a Σ r_x² - b Σ r_x r_y
//   z:  -Σ r_y c r_y                        = -c Σ r_y²
// so
//   -(Σ r_y²) c                          = H'_z
//   (Σ r_x r_y) a + (Σ r_y²) b           = H'_x
//   -(Σ r_x²) a - (Σ r_x r_y) b          = H'_y - (Σ r_y r_z) c
// (eq. 2.7 as printed in Ridgely 2001 has the sign of the Σ r_y r_z c term wrong).
// The 2×2 determinant is Σr_x² Σr_y² - (Σ r_x r_y)² ≥ 0 (Cauchy-Schwarz); it is
// zero iff all (r_x, r_y) are proportional, i.e. the hips project onto one line
// through the CoM (e.g. a trot diagonal pair).
//
// The additions also change the net impulse by (c Σ r_y, 0, a Σ r_x + b Σ r_y),
// which vanishes iff Σ r_x = Σ r_y = 0. With additionally a common r_z, every
// moment term above is exact, so the scheme reproduces (P_x, P_z, H) exactly.
// Its solution then has the form p_x,i = α + c r_y,i, p_z,i = β + a r_x,i +
// b r_y,i, which is exactly the row space of A (with r_z common), so it equals
// the minimum-norm solution. For other layouts the scheme is not exact; the
// residual is reported.
// ---------------------------------------------------------------------------
#include "sim/control/allocation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

namespace pronk::control {
namespace {

using Vec5 = Eigen::Matrix<double, 5, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

constexpr int kFixedMaxLegs = 8;          ///< legs handled without heap allocation in the solver
constexpr double kRankThreshold = 1e-10;  ///< COD pivots below this × the largest count as zero
constexpr double kTiny = 1e-300;
constexpr std::array<const char*, 6> kComponentNames = {"P_x", "P_y", "P_z", "H_x", "H_y", "H_z"};

std::string format(const char* fmt, double a) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

std::string format3(const char* fmt, double a, double b, double c) {
  char buf[200];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

void append(std::string& message, const std::string& part) {
  if (part.empty()) return;
  if (!message.empty()) message += "; ";
  message += part;
}

Vec6 stack(const Vec3& P, const Vec3& H) {
  Vec6 v;
  v << P, H;
  return v;
}

/// Fills produced_P, produced_H and relative_residual from leg_impulse.
void fill_produced(const std::vector<LegSlot>& legs, const Vec3& P, const Vec3& H,
                   AllocationResult& result) {
  result.produced_P.setZero();
  result.produced_H.setZero();
  for (std::size_t i = 0; i < legs.size(); ++i) {
    if (!legs[i].active) continue;
    result.produced_P += result.leg_impulse[i];
    result.produced_H += legs[i].hip_body.cross(result.leg_impulse[i]);
  }
  const Vec6 request = stack(P, H);
  const Vec6 produced = stack(result.produced_P, result.produced_H);
  result.relative_residual = (request - produced).norm() / std::max(request.norm(), kTiny);
}

/// "unproduced components: H_x, H_z" for components (other than P_y, which is
/// reported separately) whose residual exceeds tol relative to |(P, H)|.
std::string unproduced_components(const Vec3& P, const Vec3& H, const AllocationResult& result,
                                  double tol) {
  const Vec6 request = stack(P, H);
  const Vec6 residual = request - stack(result.produced_P, result.produced_H);
  const double scale = std::max(request.norm(), kTiny);
  std::string list;
  for (int k = 0; k < 6; ++k) {
    if (k == 1) continue;
    if (std::abs(residual[k]) / scale > tol) {
      if (!list.empty()) list += ", ";
      list += kComponentNames[static_cast<std::size_t>(k)];
    }
  }
  return list.empty() ? std::string() : "unproduced components: " + list;
}

std::string lateral_message(double P_y) {
  return format(
      "lateral P_y = %.3g N s cannot be produced (legs push with p_y = 0 in the body frame)", P_y);
}

/// Geometric reason why the active layout cannot produce a general (P, H).
/// Only called on the (rare) failure path.
std::string describe_layout(const std::vector<LegSlot>& legs, int rank) {
  int n = 0;
  Vec3 centroid = Vec3::Zero();
  double sumsq = 0.0;
  for (const auto& leg : legs) {
    if (!leg.active) continue;
    ++n;
    centroid += leg.hip_body;
    sumsq += leg.hip_body.squaredNorm();
  }
  if (n == 0) return "no active legs";
  centroid /= n;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double y_spread = 0.0;
  for (const auto& leg : legs) {
    if (!leg.active) continue;
    const Vec3 d = leg.hip_body - centroid;
    cov += d * d.transpose();
    y_spread = std::max(y_spread, std::abs(d.y()));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 lambda = eig.eigenvalues();  // ascending
  if (n == 1 || lambda[2] <= 1e-18 * sumsq) {
    return "active hips coincide at a single point: only H = r x P is producible, H cannot be "
           "set independently of P";
  }
  if (lambda[1] <= 1e-12 * lambda[2]) {
    const Vec3 dir = eig.eigenvectors().col(2);
    return format3(
               "active legs are collinear (line direction (%.3f, %.3f, %.3f)): cannot produce H "
               "about the leg line",
               dir.x(), dir.y(), dir.z()) +
           (n == 2 ? " (only two active legs)" : "");
  }
  const double length = std::sqrt(sumsq / n);
  if (y_spread <= 1e-9 * length) {
    return format(
        "active hips all lie in one body x-z plane (r_y = %.4g m): H_x and H_z are tied to P "
        "(H_x = r_y P_z, H_z = -r_y P_x)",
        centroid.y());
  }
  if (rank < 5) return format("active layout is rank deficient (rank %.0f of 5)", rank);
  return "active layout is ill-conditioned";
}

/// Minimum-norm least-squares solve of A x = b (A is 5 × 2N). Returns the
/// numerical rank. The complete orthogonal decomposition is taken of Aᵀ
/// (2N × 5) and solved transposed: for a full-row-rank A (the normal case) the
/// Z factor is the identity, so with the compile-time bound MaxRows on 2N the
/// solve needs no heap memory; Eigen allocates a small temporary only for
/// rank-deficient layouts (and Eigen's JacobiSVD on these shapes triggers
/// spurious GCC -Wmaybe-uninitialized warnings, hence the COD).
template <int MaxRows>
int solve_minimum_norm(const std::vector<LegSlot>& legs, int n_active, const Vec5& b,
                       std::vector<Vec3>& impulses) {
  using MatAT = Eigen::Matrix<double, Eigen::Dynamic, 5, Eigen::ColMajor, MaxRows, 5>;
  using VecX = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MaxRows, 1>;
  MatAT At(2 * n_active, 5);
  Eigen::Index k = 0;
  for (const auto& leg : legs) {
    if (!leg.active) continue;
    const Vec3& r = leg.hip_body;
    At.row(k) << 1.0, 0.0, 0.0, r.z(), -r.y();      // p_x
    At.row(k + 1) << 0.0, 1.0, r.y(), -r.x(), 0.0;  // p_z
    k += 2;
  }
  Eigen::CompleteOrthogonalDecomposition<MatAT> cod(At.rows(), 5);
  cod.setThreshold(kRankThreshold);
  cod.compute(At);
  const VecX x = cod.transpose().solve(b);
  k = 0;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    if (!legs[i].active) continue;
    impulses[i] = Vec3(x[k], 0.0, x[k + 1]);
    k += 2;
  }
  return static_cast<int>(cod.rank());
}

void allocate_minimum_norm(const std::vector<LegSlot>& legs, int n_active, const Vec3& P,
                           const Vec3& H, const AllocationOptions& options,
                           AllocationResult& result) {
  const Vec6 request = stack(P, H);
  const double scale = std::max(request.norm(), kTiny);
  const bool lateral = std::abs(P.y()) / scale > options.residual_tol;

  Vec5 b;
  b << P.x(), P.z(), H.x(), H.y(), H.z();
  int rank = 0;
  if (n_active > 0 && b.squaredNorm() > 0.0) {
    rank = n_active <= kFixedMaxLegs
               ? solve_minimum_norm<2 * kFixedMaxLegs>(legs, n_active, b, result.leg_impulse)
               : solve_minimum_norm<Eigen::Dynamic>(legs, n_active, b, result.leg_impulse);
  }
  fill_produced(legs, P, H, result);

  // Residual of the producible part (everything except P_y).
  Vec6 rest_residual = request - stack(result.produced_P, result.produced_H);
  rest_residual[1] = 0.0;
  const bool rest_infeasible = rest_residual.norm() / scale > options.residual_tol;

  if (lateral || rest_infeasible) {
    result.status = AllocationStatus::kInfeasible;
    if (lateral) append(result.message, lateral_message(P.y()));
    if (rest_infeasible) {
      append(result.message, describe_layout(legs, rank));
      append(result.message, unproduced_components(P, H, result, options.residual_tol));
    }
  }

  // Per-leg limits: uniform scaling so the largest |p_i| equals the limit.
  const double limit = options.max_leg_impulse;
  if (limit > 0.0 && std::isfinite(limit)) {
    double largest = 0.0;
    for (const auto& p : result.leg_impulse) largest = std::max(largest, p.norm());
    if (largest > limit) {
      const double s = limit / largest;
      for (auto& p : result.leg_impulse) p *= s;
      fill_produced(legs, P, H, result);
      append(result.message,
             format3("leg impulse limit active: largest |p_i| = %.4g N s exceeds max_leg_impulse = "
                     "%.4g N s; all leg impulses scaled by %.4g",
                     largest, limit, s));
      // kInfeasible (the request is outside the layout's reach) takes precedence.
      if (result.status == AllocationStatus::kOk) result.status = AllocationStatus::kLimited;
    }
  }
}

/// Layout sums over the active legs (the seed scheme's closed form).
struct SeedLayoutSums {
  double Sx = 0, Sy = 0, Sxx = 0, Syy = 0, Sxy = 0, Syz = 0, sumsq = 0;
  double zmin = std::numeric_limits<double>::infinity();
  double zmax = -std::numeric_limits<double>::infinity();
  Vec3 Sr = Vec3::Zero();
};

SeedLayoutSums seed_layout_sums(const std::vector<LegSlot>& legs) {
  SeedLayoutSums s;
  for (const auto& leg : legs) {
    if (!leg.active) continue;
    const Vec3& r = leg.hip_body;
    s.Sr += r;
    s.Sx += r.x();
    s.Sy += r.y();
    s.Sxx += r.x() * r.x();
    s.Syy += r.y() * r.y();
    s.Sxy += r.x() * r.y();
    s.Syz += r.y() * r.z();
    s.sumsq += r.squaredNorm();
    s.zmin = std::min(s.zmin, r.z());
    s.zmax = std::max(s.zmax, r.z());
  }
  return s;
}

/// The additions c r_y (x) and a r_x + b r_y (z) that produce the moment Hres.
struct SeedCoefficients {
  double a = 0.0, b = 0.0, c = 0.0;
  bool singular_c = false;   ///< sum of r_y^2 ~ 0: H_z cannot be allocated
  bool singular_ab = false;  ///< the 2x2 system for a, b is singular
};

SeedCoefficients seed_coefficients(const SeedLayoutSums& s, const Vec3& Hres) {
  SeedCoefficients k;
  const double Sxx = s.Sxx, Syy = s.Syy, Sxy = s.Sxy, Syz = s.Syz;
  const double Sxy_scale = Sxx + Syy;
  if (Syy > 1e-12 * Sxy_scale && Syy > 0.0) {
    k.c = -Hres.z() / Syy;
  } else {
    k.singular_c = true;
  }
  const double det = Sxx * Syy - Sxy * Sxy;
  const double rhs_x = Hres.x();
  const double rhs_y = Hres.y() - Syz * k.c;
  if (det > 1e-12 * Sxy_scale * Sxy_scale && det > 0.0) {
    // [Sxy  Syy] [a]   [rhs_x]
    // [-Sxx -Sxy] [b] = [rhs_y]
    k.a = (-Sxy * rhs_x - Syy * rhs_y) / det;
    k.b = (Sxx * rhs_x + Sxy * rhs_y) / det;
  } else {
    k.singular_ab = true;
    if (Sxy_scale > 0.0) {  // least-squares best effort
      Eigen::Matrix2d M;
      M << Sxy, Syy, -Sxx, -Sxy;
      Eigen::JacobiSVD<Eigen::Matrix2d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
      svd.setThreshold(1e-12);
      const Eigen::Vector2d ab = svd.solve(Eigen::Vector2d(rhs_x, rhs_y));
      k.a = ab[0];
      k.b = ab[1];
    }
  }
  return k;
}

void allocate_seed(const std::vector<LegSlot>& legs, int n_active, const Vec3& P, const Vec3& H,
                   const AllocationOptions& options, AllocationResult& result) {
  const Vec6 request = stack(P, H);
  const double scale = std::max(request.norm(), kTiny);
  const bool lateral = std::abs(P.y()) / scale > options.residual_tol;

  if (n_active == 0) {
    fill_produced(legs, P, H, result);
    if (result.relative_residual > options.residual_tol) {
      result.status = AllocationStatus::kInfeasible;
      append(result.message, "no active legs");
    }
    return;
  }

  const SeedLayoutSums sums = seed_layout_sums(legs);
  const double n = n_active;
  const double length = std::sqrt(sums.sumsq / n);
  const bool symmetric = std::abs(sums.Sx) <= 1e-9 * n * length &&
                         std::abs(sums.Sy) <= 1e-9 * n * length &&
                         sums.zmax - sums.zmin <= 1e-9 * length;

  // Equal share of P (P_y dropped) and the moment it leaves to the additions.
  const Vec3 share(P.x() / n, 0.0, P.z() / n);
  const Vec3 Hres = H - sums.Sr.cross(share);
  const SeedCoefficients k = seed_coefficients(sums, Hres);

  for (std::size_t i = 0; i < legs.size(); ++i) {
    if (!legs[i].active) continue;
    const Vec3& r = legs[i].hip_body;
    result.leg_impulse[i] = share + Vec3(k.c * r.y(), 0.0, k.a * r.x() + k.b * r.y());
  }
  fill_produced(legs, P, H, result);

  Vec6 rest_residual = request - stack(result.produced_P, result.produced_H);
  rest_residual[1] = 0.0;
  const bool rest_infeasible = rest_residual.norm() / scale > options.residual_tol;
  if (lateral || rest_infeasible) {
    result.status = AllocationStatus::kInfeasible;
    if (lateral) append(result.message, lateral_message(P.y()));
    if (rest_infeasible) {
      if (k.singular_c) {
        append(result.message,
               "seed scheme: sum of r_y^2 over active legs is ~0, H_z cannot be allocated");
      }
      if (k.singular_ab) {
        append(result.message,
               "seed scheme: active hips project onto one line through the CoM (2x2 system for "
               "a, b singular), H_x/H_y cannot be allocated independently");
      }
      if (!symmetric) {
        append(result.message, "seed scheme is exact only for symmetric layouts; use minimum_norm");
      }
      append(result.message, unproduced_components(P, H, result, options.residual_tol));
    }
  }
}

}  // namespace

AllocationResult allocate(const std::vector<LegSlot>& legs, const Vec3& P, const Vec3& H,
                          const AllocationOptions& options) {
  AllocationResult result;
  result.leg_impulse.assign(legs.size(), Vec3::Zero());

  int n_active = 0;
  bool finite = P.allFinite() && H.allFinite();
  for (const auto& leg : legs) {
    if (!leg.active) continue;
    ++n_active;
    finite = finite && leg.hip_body.allFinite();
  }
  if (!finite) {
    result.status = AllocationStatus::kInfeasible;
    result.message = "non-finite request or active hip position; no impulses allocated";
    result.relative_residual = std::numeric_limits<double>::infinity();
    return result;
  }

  if (options.scheme == AllocationScheme::kSeed) {
    allocate_seed(legs, n_active, P, H, options, result);
  } else {
    allocate_minimum_norm(legs, n_active, P, H, options, result);
  }
  return result;
}

}  // namespace pronk::control
