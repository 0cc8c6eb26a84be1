// Tests for sim/control/allocation: independent references (sums recomputed
// here, pseudo-inverse via JacobiSVD built here) rather than produced_*.
#include "sim/control/allocation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

using pronk::control::allocate;
using pronk::control::AllocationOptions;
using pronk::control::AllocationResult;
using pronk::control::AllocationScheme;
using pronk::control::AllocationStatus;
using pronk::control::LegSlot;
using pronk::control::Vec3;

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct Sums {
  Vec3 P = Vec3::Zero();
  Vec3 H = Vec3::Zero();
};

Sums recompute(const std::vector<LegSlot>& legs, const std::vector<Vec3>& p) {
  Sums s;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    s.P += p[i];
    s.H += legs[i].hip_body.cross(p[i]);
  }
  return s;
}

double relative_error(const std::vector<LegSlot>& legs, const std::vector<Vec3>& p, const Vec3& P,
                      const Vec3& H) {
  const Sums s = recompute(legs, p);
  Vec6 req, got;
  req << P, H;
  got << s.P, s.H;
  return (req - got).norm() / std::max(req.norm(), 1e-300);
}

bool all_finite(const AllocationResult& r) {
  for (const auto& p : r.leg_impulse)
    if (!p.allFinite()) return false;
  return r.produced_P.allFinite() && r.produced_H.allFinite() && std::isfinite(r.relative_residual);
}

/// Independent reference: A built from scratch over the active legs, 6 rows
/// (P_x, P_y, P_z, H_x, H_y, H_z) with unknowns (p_x, p_z) per active leg.
Eigen::MatrixXd build_A(const std::vector<LegSlot>& legs) {
  std::vector<Vec3> act;
  for (const auto& l : legs)
    if (l.active) act.push_back(l.hip_body);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 2 * static_cast<Eigen::Index>(act.size()));
  for (std::size_t i = 0; i < act.size(); ++i) {
    // Column = (unit force, r × unit force) for e_x and e_z.
    const Vec3 ex(1, 0, 0), ez(0, 0, 1);
    A.col(2 * i).head<3>() = ex;
    A.col(2 * i).tail<3>() = act[i].cross(ex);
    A.col(2 * i + 1).head<3>() = ez;
    A.col(2 * i + 1).tail<3>() = act[i].cross(ez);
  }
  return A;
}

Eigen::VectorXd stack_active(const std::vector<LegSlot>& legs, const std::vector<Vec3>& p) {
  std::vector<double> v;
  for (std::size_t i = 0; i < legs.size(); ++i) {
    if (!legs[i].active) continue;
    v.push_back(p[i].x());
    v.push_back(p[i].z());
  }
  return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

Eigen::VectorXd pinv_solution(const std::vector<LegSlot>& legs, const Vec3& P, const Vec3& H) {
  // Pad to a square matrix (zero rows/columns do not change the minimum-norm
  // least-squares solution) so a plain two-sided Jacobi SVD applies.
  const Eigen::MatrixXd A = build_A(legs);
  const Eigen::Index m = std::max<Eigen::Index>(6, A.cols());
  Eigen::MatrixXd Ab = Eigen::MatrixXd::Zero(m, m);
  Ab.topLeftCorner(6, A.cols()) = A;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  b.head<3>() = P;
  b.segment<3>(3) = H;
  Eigen::JacobiSVD<Eigen::MatrixXd, Eigen::NoQRPreconditioner> svd(
      Ab, Eigen::ComputeFullU | Eigen::ComputeFullV);
  svd.setThreshold(1e-10);
  const Eigen::VectorXd x = svd.solve(b);
  return x.head(A.cols());
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vec3 random_vec(std::mt19937_64& rng, double half) {
  return Vec3(uniform(rng, -half, half), uniform(rng, -half, half), uniform(rng, -half, half));
}

AllocationOptions options_for(AllocationScheme s) {
  AllocationOptions o;
  o.scheme = s;
  return o;
}

std::vector<LegSlot> corners(double a, double b, double z0) {
  return {{Vec3(a, b, z0), true},
          {Vec3(a, -b, z0), true},
          {Vec3(-a, b, z0), true},
          {Vec3(-a, -b, z0), true}};
}

double max_abs_diff(const std::vector<Vec3>& x, const std::vector<Vec3>& y) {
  double m = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) m = std::max(m, (x[i] - y[i]).cwiseAbs().maxCoeff());
  return m;
}

double max_norm(const std::vector<Vec3>& x) {
  double m = 0.0;
  for (const auto& p : x) m = std::max(m, p.norm());
  return m;
}

}  // namespace

TEST_CASE("minimum-norm reproduces random requests on random layouts exactly", "[allocation]") {
  std::mt19937_64 rng(20240611);
  const AllocationOptions opt = options_for(AllocationScheme::kMinimumNorm);
  double worst_residual = 0.0, worst_pinv = 0.0, worst_null = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const int n = std::uniform_int_distribution<int>(3, 8)(rng);
    std::vector<LegSlot> legs(static_cast<std::size_t>(n));
    for (auto& l : legs) l.hip_body = random_vec(rng, 0.3);
    const Vec3 P(uniform(rng, -10, 10), 0.0, uniform(rng, -10, 10));
    const Vec3 H = random_vec(rng, 3.0);

    const AllocationResult r = allocate(legs, P, H, opt);
    REQUIRE(r.status == AllocationStatus::kOk);
    REQUIRE(r.message.empty());
    REQUIRE(r.leg_impulse.size() == legs.size());
    for (const auto& p : r.leg_impulse) REQUIRE(p.y() == 0.0);
    worst_residual = std::max(worst_residual, relative_error(legs, r.leg_impulse, P, H));

    // Minimum norm, reference 1: independent pseudo-inverse.
    const Eigen::VectorXd x = stack_active(legs, r.leg_impulse);
    const Eigen::VectorXd ref = pinv_solution(legs, P, H);
    worst_pinv = std::max(worst_pinv, (x - ref).norm() / ref.norm());

    // Reference 2: x is orthogonal to null(A) (basis from a full-pivoting LU),
    // so adding any null-space vector grows its norm.
    const Eigen::MatrixXd A = build_A(legs);
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    REQUIRE(lu.rank() == 5);
    Eigen::MatrixXd N = lu.kernel();
    REQUIRE(N.cols() == A.cols() - 5);
    for (Eigen::Index k = 0; k < N.cols(); ++k) N.col(k).normalize();
    worst_null = std::max(worst_null, (N.transpose() * x).norm() / x.norm());
    for (Eigen::Index k = 0; k < N.cols(); ++k) {
      REQUIRE((A * N.col(k)).norm() <= 1e-12);
      const double t = 1e-3 * x.norm();
      REQUIRE((x + t * N.col(k)).norm() > x.norm());
      REQUIRE((x - t * N.col(k)).norm() > x.norm());
    }
    // produced_* agree with the sums.
    const Sums s = recompute(legs, r.leg_impulse);
    REQUIRE((s.P - r.produced_P).norm() <= 1e-12 * (1 + s.P.norm()));
    REQUIRE((s.H - r.produced_H).norm() <= 1e-12 * (1 + s.H.norm()));
    REQUIRE(r.relative_residual <= 1e-12);
  }
  INFO("worst residual " << worst_residual << " pinv " << worst_pinv << " null " << worst_null);
  CHECK(worst_residual <= 1e-12);
  CHECK(worst_pinv <= 1e-12);
  CHECK(worst_null <= 1e-12);
}

TEST_CASE("seed scheme equals minimum-norm on symmetric layouts", "[allocation]") {
  std::mt19937_64 rng(7);
  const AllocationOptions seed = options_for(AllocationScheme::kSeed);
  const AllocationOptions mn = options_for(AllocationScheme::kMinimumNorm);
  for (int trial = 0; trial < 300; ++trial) {
    const double a = uniform(rng, 0.1, 0.4);
    const double b = uniform(rng, 0.05, 0.3);
    const double z0 = (trial % 3 == 0) ? -0.04 : (trial % 3 == 1 ? 0.0 : uniform(rng, -0.2, 0.1));
    std::vector<LegSlot> legs;
    switch (trial % 3) {
      case 0:  // quadruped corners
        legs = corners(a, b, z0);
        break;
      case 1: {  // hexapod: corners plus a middle pair
        legs = corners(a, b, z0);
        const double bm = uniform(rng, 0.05, 0.4);
        legs.push_back({Vec3(0, bm, z0), true});
        legs.push_back({Vec3(0, -bm, z0), true});
        break;
      }
      default: {  // random centrally symmetric pairs (Σr_x = Σr_y = 0), common r_z
        const int pairs = std::uniform_int_distribution<int>(2, 4)(rng);
        for (int k = 0; k < pairs; ++k) {
          const double x = uniform(rng, -0.3, 0.3), y = uniform(rng, -0.3, 0.3);
          legs.push_back({Vec3(x, y, z0), true});
          legs.push_back({Vec3(-x, -y, z0), true});
        }
      }
    }
    const Vec3 P(uniform(rng, -10, 10), 0.0, uniform(rng, 0, 20));
    const Vec3 H = random_vec(rng, 3.0);
    const AllocationResult rs = allocate(legs, P, H, seed);
    const AllocationResult rm = allocate(legs, P, H, mn);
    INFO("trial " << trial << " message " << rs.message);
    REQUIRE(rs.status == AllocationStatus::kOk);
    REQUIRE(rm.status == AllocationStatus::kOk);
    REQUIRE(relative_error(legs, rs.leg_impulse, P, H) <= 1e-12);
    REQUIRE(max_abs_diff(rs.leg_impulse, rm.leg_impulse) <= 1e-12 * max_norm(rm.leg_impulse));
    for (const auto& p : rs.leg_impulse) REQUIRE(p.y() == 0.0);
  }
}

TEST_CASE("seed scheme P_x with hips below the CoM needs the r_z P_x correction", "[allocation]") {
  // Pure forward impulse, no moment requested: the equal share alone would
  // produce H_y = z0 P_x; the corrected scheme cancels it.
  const auto legs = corners(0.2, 0.1, -0.04);
  const Vec3 P(4.0, 0.0, 10.0), H = Vec3::Zero();
  const AllocationResult r = allocate(legs, P, H, options_for(AllocationScheme::kSeed));
  CHECK(r.status == AllocationStatus::kOk);
  CHECK(relative_error(legs, r.leg_impulse, P, H) <= 1e-14);
  const Sums naive = recompute(legs, std::vector<Vec3>(4, Vec3(1.0, 0.0, 2.5)));
  CHECK(std::abs(naive.H.y() - (-0.04 * 4.0)) <= 1e-14);  // what the seed would leave
}

TEST_CASE("seed scheme on asymmetric layout reports residual", "[allocation]") {
  std::vector<LegSlot> legs = {{Vec3(0.3, 0.1, 0), true},
                               {Vec3(0.2, -0.15, 0), true},
                               {Vec3(-0.1, 0.12, -0.02), true},
                               {Vec3(-0.25, -0.1, 0), true}};
  const Vec3 P(3, 0, 12), H(0.4, -0.7, 0.2);
  const AllocationResult r = allocate(legs, P, H, options_for(AllocationScheme::kSeed));
  CHECK(r.status == AllocationStatus::kInfeasible);
  CHECK(r.message.find("symmetric") != std::string::npos);
  CHECK(r.relative_residual > 1e-9);
  CHECK(std::abs(r.relative_residual - relative_error(legs, r.leg_impulse, P, H)) <= 1e-14);
  CHECK(all_finite(r));
  // Minimum-norm is exact on the same layout.
  const AllocationResult m = allocate(legs, P, H, options_for(AllocationScheme::kMinimumNorm));
  CHECK(m.status == AllocationStatus::kOk);
  CHECK(relative_error(legs, m.leg_impulse, P, H) <= 1e-12);
}

TEST_CASE("seed scheme singular layout (diagonal pair) is flagged", "[allocation]") {
  auto legs = corners(0.2, 0.1, 0.0);
  legs[1].active = false;
  legs[2].active = false;
  const Vec3 P(1, 0, 10), H(0.5, 0.3, -0.2);
  const AllocationResult r = allocate(legs, P, H, options_for(AllocationScheme::kSeed));
  CHECK(r.status == AllocationStatus::kInfeasible);
  CHECK(r.message.find("singular") != std::string::npos);
  CHECK(all_finite(r));
  CHECK(r.leg_impulse[1] == Vec3::Zero());
  CHECK(r.leg_impulse[2] == Vec3::Zero());
}

TEST_CASE("disabled leg gets zero and min-norm stays exact", "[allocation]") {
  std::mt19937_64 rng(99);
  for (int disabled = 0; disabled < 4; ++disabled) {
    auto legs = corners(0.25, 0.12, -0.04);
    legs[static_cast<std::size_t>(disabled)].active = false;
    const Vec3 P(uniform(rng, -5, 5), 0, uniform(rng, 5, 15));
    const Vec3 H = random_vec(rng, 2.0);
    const AllocationResult r = allocate(legs, P, H, options_for(AllocationScheme::kMinimumNorm));
    CHECK(r.status == AllocationStatus::kOk);
    CHECK(r.leg_impulse[static_cast<std::size_t>(disabled)] == Vec3::Zero());
    CHECK(relative_error(legs, r.leg_impulse, P, H) <= 1e-12);
    const Eigen::VectorXd ref = pinv_solution(legs, P, H);
    CHECK((stack_active(legs, r.leg_impulse) - ref).norm() <= 1e-10 * ref.norm());
  }
}

TEST_CASE("trot diagonal pair: infeasible in general, exact in its span", "[allocation]") {
  std::mt19937_64 rng(5);
  auto legs = corners(0.25, 0.12, -0.04);
  legs[1].active = false;  // active: (a, b) and (-a, -b)
  legs[2].active = false;
  const AllocationOptions opt = options_for(AllocationScheme::kMinimumNorm);

  SECTION("generic request") {
    const Vec3 P(2, 0, 10), H(0.3, -0.4, 0.5);
    const AllocationResult r = allocate(legs, P, H, opt);
    CHECK(r.status == AllocationStatus::kInfeasible);
    CHECK(r.message.find("collinear") != std::string::npos);
    CHECK(r.message.find("leg line") != std::string::npos);
    CHECK(r.relative_residual > 1e-9);
    CHECK(std::abs(r.relative_residual - relative_error(legs, r.leg_impulse, P, H)) <= 1e-14);
    CHECK(all_finite(r));
    CHECK(r.leg_impulse[1] == Vec3::Zero());
    CHECK(r.leg_impulse[2] == Vec3::Zero());
    // Best effort is the least-squares minimum-norm solution.
    const Eigen::VectorXd ref = pinv_solution(legs, P, H);
    CHECK((stack_active(legs, r.leg_impulse) - ref).norm() <= 1e-10 * ref.norm());
  }
  SECTION("requests in the pair's span") {
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<Vec3> p(4, Vec3::Zero());
      p[0] = Vec3(uniform(rng, -3, 3), 0, uniform(rng, 0, 10));
      p[3] = Vec3(uniform(rng, -3, 3), 0, uniform(rng, 0, 10));
      const Sums s = recompute(legs, p);
      const AllocationResult r = allocate(legs, s.P, s.H, opt);
      CHECK(r.status == AllocationStatus::kOk);
      CHECK(relative_error(legs, r.leg_impulse, s.P, s.H) <= 1e-12);
      CHECK(r.leg_impulse[1] == Vec3::Zero());
      CHECK(r.leg_impulse[2] == Vec3::Zero());
      // Minimum norm: never larger than the generating impulses.
      CHECK(stack_active(legs, r.leg_impulse).norm() <= stack_active(legs, p).norm() * (1 + 1e-12));
    }
  }
}

TEST_CASE("collinear layouts are infeasible without NaN", "[allocation]") {
  const AllocationOptions opt = options_for(AllocationScheme::kMinimumNorm);
  const Vec3 P(1, 0, 8), H(0.2, 0.3, -0.1);
  SECTION("generic line") {
    const Vec3 r0(0.1, -0.05, -0.03), d = Vec3(0.7, 0.4, 0.1).normalized();
    std::vector<LegSlot> legs;
    for (double t : {-0.3, -0.1, 0.05, 0.2, 0.35}) legs.push_back({r0 + t * d, true});
    const AllocationResult r = allocate(legs, P, H, opt);
    CHECK(r.status == AllocationStatus::kInfeasible);
    CHECK(r.message.find("collinear") != std::string::npos);
    CHECK(all_finite(r));
    const Eigen::VectorXd ref = pinv_solution(legs, P, H);
    CHECK((stack_active(legs, r.leg_impulse) - ref).norm() <= 1e-9 * ref.norm());
    CHECK(std::abs(r.relative_residual - relative_error(legs, r.leg_impulse, P, H)) <= 1e-14);
  }
  SECTION("line along body x") {
    std::vector<LegSlot> legs;
    for (double x : {-0.3, 0.0, 0.3}) legs.push_back({Vec3(x, 0, 0), true});
    const AllocationResult r = allocate(legs, P, H, opt);
    CHECK(r.status == AllocationStatus::kInfeasible);
    CHECK(!r.message.empty());
    CHECK(r.message.find("H_x") != std::string::npos);
    CHECK(r.message.find("H_z") != std::string::npos);
    CHECK(all_finite(r));
    // The producible components are produced.
    const Sums s = recompute(legs, r.leg_impulse);
    CHECK(std::abs(s.P.x() - P.x()) <= 1e-12);
    CHECK(std::abs(s.P.z() - P.z()) <= 1e-12);
    CHECK(std::abs(s.H.y() - H.y()) <= 1e-12);
  }
  SECTION("single leg and coincident hips") {
    std::vector<LegSlot> one = {{Vec3(0.1, 0.1, 0), true}};
    const AllocationResult r1 = allocate(one, P, H, opt);
    CHECK(r1.status == AllocationStatus::kInfeasible);
    CHECK(!r1.message.empty());
    CHECK(all_finite(r1));
    std::vector<LegSlot> same(3, LegSlot{Vec3(0.1, 0.1, 0), true});
    const AllocationResult r3 = allocate(same, P, H, opt);
    CHECK(r3.status == AllocationStatus::kInfeasible);
    CHECK(r3.message.find("coincide") != std::string::npos);
    CHECK(all_finite(r3));
  }
  SECTION("hips in one x-z plane") {
    std::vector<LegSlot> legs = {
        {Vec3(0.2, 0, 0), true}, {Vec3(-0.2, 0, 0), true}, {Vec3(0, 0, -0.1), true}};
    const AllocationResult r = allocate(legs, P, H, opt);
    CHECK(r.status == AllocationStatus::kInfeasible);
    CHECK(r.message.find("x-z plane") != std::string::npos);
    CHECK(all_finite(r));
  }
}

TEST_CASE("lateral P_y is infeasible, the rest is allocated", "[allocation]") {
  const auto legs = corners(0.25, 0.12, -0.04);
  const Vec3 P(2, 1.5, 10), H(0.3, -0.2, 0.1);
  for (auto scheme : {AllocationScheme::kMinimumNorm, AllocationScheme::kSeed}) {
    const AllocationResult r = allocate(legs, P, H, options_for(scheme));
    CHECK(r.status == AllocationStatus::kInfeasible);
    CHECK(r.message.find("P_y") != std::string::npos);
    CHECK(all_finite(r));
    const Sums s = recompute(legs, r.leg_impulse);
    CHECK(s.P.y() == 0.0);
    CHECK(std::abs(s.P.x() - P.x()) <= 1e-12);
    CHECK(std::abs(s.P.z() - P.z()) <= 1e-12);
    CHECK((s.H - H).norm() <= 1e-12);
    CHECK(std::abs(r.relative_residual - 1.5 / std::sqrt(P.squaredNorm() + H.squaredNorm())) <=
          1e-12);
  }
}

TEST_CASE("leg limits scale impulses uniformly", "[allocation]") {
  const auto legs = corners(0.25, 0.12, -0.04);
  const Vec3 P(3, 0, 20), H(0.5, -0.8, 0.2);
  AllocationOptions opt = options_for(AllocationScheme::kMinimumNorm);
  const AllocationResult free = allocate(legs, P, H, opt);
  REQUIRE(free.status == AllocationStatus::kOk);
  const double largest = max_norm(free.leg_impulse);

  opt.max_leg_impulse = 0.6 * largest;
  const AllocationResult r = allocate(legs, P, H, opt);
  CHECK(r.status == AllocationStatus::kLimited);
  CHECK(!r.message.empty());
  CHECK(std::abs(max_norm(r.leg_impulse) - opt.max_leg_impulse) <= 1e-12 * opt.max_leg_impulse);
  for (std::size_t i = 0; i < legs.size(); ++i) {
    CHECK((r.leg_impulse[i] - 0.6 * free.leg_impulse[i]).norm() <= 1e-12 * largest);
  }
  CHECK(std::abs(r.relative_residual - 0.4) <= 1e-12);
  CHECK(std::abs(r.relative_residual - relative_error(legs, r.leg_impulse, P, H)) <= 1e-14);

  // A limit that is not reached changes nothing.
  opt.max_leg_impulse = 2.0 * largest;
  const AllocationResult loose = allocate(legs, P, H, opt);
  CHECK(loose.status == AllocationStatus::kOk);
  CHECK(max_abs_diff(loose.leg_impulse, free.leg_impulse) == 0.0);
  // Infinite limit: no limit.
  opt.max_leg_impulse = std::numeric_limits<double>::infinity();
  CHECK(allocate(legs, P, H, opt).status == AllocationStatus::kOk);
}

TEST_CASE("zero request gives zero impulses", "[allocation]") {
  for (auto scheme : {AllocationScheme::kMinimumNorm, AllocationScheme::kSeed}) {
    for (bool collinear : {false, true}) {
      auto legs = corners(0.25, 0.12, -0.04);
      if (collinear) {
        legs[1].active = false;
        legs[2].active = false;
      }
      const AllocationResult r = allocate(legs, Vec3::Zero(), Vec3::Zero(), options_for(scheme));
      CHECK(r.status == AllocationStatus::kOk);
      CHECK(r.message.empty());
      CHECK(r.relative_residual == 0.0);
      for (const auto& p : r.leg_impulse) CHECK(p == Vec3::Zero());
      CHECK(r.produced_P == Vec3::Zero());
      CHECK(r.produced_H == Vec3::Zero());
    }
  }
}

TEST_CASE("more than eight legs and edge cases", "[allocation]") {
  std::mt19937_64 rng(3);
  const AllocationOptions opt = options_for(AllocationScheme::kMinimumNorm);
  std::vector<LegSlot> legs(12);
  for (auto& l : legs) l.hip_body = random_vec(rng, 0.3);
  legs[4].active = false;
  const Vec3 P(1, 0, 9), H(0.1, 0.2, 0.3);
  const AllocationResult r = allocate(legs, P, H, opt);
  CHECK(r.status == AllocationStatus::kOk);
  CHECK(relative_error(legs, r.leg_impulse, P, H) <= 1e-12);
  CHECK(r.leg_impulse[4] == Vec3::Zero());
  const Eigen::VectorXd ref = pinv_solution(legs, P, H);
  CHECK((stack_active(legs, r.leg_impulse) - ref).norm() <= 1e-10 * ref.norm());

  for (auto& l : legs) l.active = false;
  const AllocationResult none = allocate(legs, P, H, opt);
  CHECK(none.status == AllocationStatus::kInfeasible);
  CHECK(none.message.find("no active legs") != std::string::npos);
  CHECK(none.relative_residual == 1.0);
  const AllocationResult none_seed = allocate(legs, P, H, options_for(AllocationScheme::kSeed));
  CHECK(none_seed.status == AllocationStatus::kInfeasible);

  const AllocationResult empty = allocate({}, Vec3::Zero(), Vec3::Zero(), opt);
  CHECK(empty.status == AllocationStatus::kOk);
  CHECK(empty.leg_impulse.empty());

  const AllocationResult bad =
      allocate(corners(0.2, 0.1, 0), Vec3(std::nan(""), 0, 1), Vec3::Zero(), opt);
  CHECK(bad.status == AllocationStatus::kInfeasible);
  for (const auto& p : bad.leg_impulse) CHECK(p == Vec3::Zero());
}
