// ShiftedLu: the momentum Schur-complement factorisation of mechanical systems
// solves (s I - J) x = b to round-off, checked against the residual of the full
// matrix (the independent reference) for real and complex shifts; Jacobians that
// break the structure and non-mechanical systems fall back to the full LU. StageLu (RADAU5's
// Newton matrix with a Jacobian per stage) against the full 3n x 3n matrix.
#include <cmath>
#include <complex>
#include <random>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "sim/ode/mechanical_system.hpp"
#include "sim/ode/stiff_linear_algebra.hpp"

using pronk::ode::Vec;
using pronk::ode::detail::ShiftedLu;

namespace {

/// A stand-in for a mechanism: states (x_j, p_j) per 3-D mass, as pseudo-rigid models
/// order them. Only the structure queries matter here.
class MechanicalStub final : public pronk::ode::MechanicalSystem {
 public:
  explicit MechanicalStub(int masses) : n_(6 * masses) {}
  int dimension() const override { return n_; }
  void rhs(double, const Vec&, Vec& d) const override { d.setZero(); }
  void momentum_mask(Vec& mask) const override {
    mask.setZero(n_);
    for (int j = 0; j < n_ / 6; ++j) mask.segment<3>(6 * j + 3).setOnes();
  }
  void position_rate(const Vec&, Vec&) const override {}

 private:
  int n_;
};

/// The same states without the mechanical structure.
class PlainStub final : public pronk::ode::OdeSystem {
 public:
  explicit PlainStub(int masses) : n_(6 * masses) {}
  int dimension() const override { return n_; }
  void rhs(double, const Vec&, Vec& d) const override { d.setZero(); }

 private:
  int n_;
};

/// J = [0 W; Fx Fp] in the interleaved (x_j, p_j) layout: dx/dt = p / m_j, stiff
/// random Fx (N/m scale 1e5 / kg) and damping Fp.
Eigen::MatrixXd mechanical_jacobian(int masses, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 6 * masses;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < masses; ++j) {
    const double inv_mass = 1.0 / (0.01 + 0.5 * (1.0 + u(rng)));
    for (int a = 0; a < 3; ++a) J(6 * j + a, 6 * j + 3 + a) = inv_mass;
  }
  for (int r = 0; r < masses; ++r) {
    for (int c = 0; c < masses; ++c) {
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          J(6 * r + 3 + a, 6 * c + b) = 1e5 * u(rng);
          J(6 * r + 3 + a, 6 * c + 3 + b) = 30.0 * u(rng);
        }
      }
    }
  }
  return J;
}

Vec random_vec(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

/// Normwise backward error |(s I - J) x - b| / (|s I - J| |x| + |b|) computed with the
/// full matrix (Frobenius norms): round-off level for a backward-stable solve.
template <typename Scalar>
double residual(const Eigen::MatrixXd& J, Scalar s,
                const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& x,
                const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& b) {
  using M = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  M E = (-J).template cast<Scalar>();
  E.diagonal().array() += s;
  return (E * x - b).norm() / (E.norm() * x.norm() + b.norm());
}

}  // namespace

TEST_CASE("Schur-complement LU solves mechanical systems to round-off", "[ode][lu]") {
  std::mt19937 rng(7);
  const MechanicalStub sys(8);
  const Eigen::MatrixXd J = mechanical_jacobian(8, rng);
  const Eigen::SparseMatrix<double> Js = J.sparseView();
  const Vec b = random_vec(48, rng);
  // Shifts of RODAS4 at h = 1e-6 ... 1e-1 s (1 / (gamma h)).
  for (double s : {4e6, 4e3, 40.0}) {
    ShiftedLu<double> lu(true);
    lu.use_structure(sys);
    REQUIRE(lu.compute(Js, s));
    CHECK(lu.used_schur());
    Vec x = b;
    lu.solve(x);
    INFO("s = " << s << ", residual " << residual(J, s, x, b));
    CHECK(residual(J, s, x, b) < 1e-15);
    ShiftedLu<double> full(true);  // no structure: the plain dense LU
    REQUIRE(full.compute(Js, s));
    CHECK_FALSE(full.used_schur());
    Vec xf = b;
    full.solve(xf);
    CHECK((x - xf).norm() <= 1e-10 * xf.norm());
  }
  // RADAU5's complex shift.
  using C = std::complex<double>;
  ShiftedLu<C> lu(true);
  lu.use_structure(sys);
  const C s(3.6e3, 2.1e3);
  REQUIRE(lu.compute(Js, s));
  CHECK(lu.used_schur());
  const Eigen::VectorXcd bc = b.cast<C>() * C(1.0, -0.5);
  Eigen::VectorXcd x = bc;
  lu.solve(x);
  CHECK(residual(J, s, x, bc) < 1e-15);
}

TEST_CASE("Schur-complement LU falls back to the full LU when the structure breaks", "[ode][lu]") {
  std::mt19937 rng(11);
  Eigen::MatrixXd J = mechanical_jacobian(4, rng);
  const Vec b = random_vec(24, rng);
  // Factorises with sys's structure and checks the full LU was used and solves E x = b.
  auto check_full_lu = [&](const pronk::ode::OdeSystem& sys, bool dense) {
    ShiftedLu<double> lu(dense);
    lu.use_structure(sys);
    REQUIRE(lu.compute(J.sparseView(), 1e3));
    CHECK_FALSE(lu.used_schur());
    Vec x = b;
    lu.solve(x);
    CHECK(residual(J, 1e3, x, b) < 1e-15);
  };
  SECTION("a position rate that depends on a position") {
    J(0, 6) = 2.0;
    check_full_lu(MechanicalStub(4), true);
  }
  SECTION("a system without a mechanical split") { check_full_lu(PlainStub(4), true); }
  SECTION("sparse factorisations keep SparseLU") { check_full_lu(MechanicalStub(4), false); }
}

TEST_CASE("StageLu: the Newton matrix with a Jacobian per stage, through the momenta",
          "[ode][lu]") {
  // M = (A^-1 / h) (x) I - blockdiag(J_1, J_2, J_3) built in full (the reference) for three
  // different mechanical Jacobians; StageLu's solve must match its residual to round-off.
  std::mt19937 rng(13);
  const int masses = 4, n = 6 * masses;
  const MechanicalStub sys(masses);
  Eigen::Matrix3d a;  // Radau IIA (order 5)
  const double s6 = std::sqrt(6.0);
  a << (88 - 7 * s6) / 360, (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225, (296 + 169 * s6) / 1800,
      (88 + 7 * s6) / 360, (-2 - 3 * s6) / 225, (16 - s6) / 36, (16 + s6) / 36, 1.0 / 9.0;
  const Eigen::Matrix3d a_inv = a.inverse();
  const Eigen::MatrixXd j1 = mechanical_jacobian(masses, rng);
  Eigen::MatrixXd j2 = mechanical_jacobian(masses, rng), j3 = mechanical_jacobian(masses, rng);
  // The stages may even differ in their position rates (W_i).
  j3(0, 3) *= 2.0;
  const Eigen::SparseMatrix<double> s1 = j1.sparseView(), s2 = j2.sparseView(),
                                    s3 = j3.sparseView();
  for (double h : {1e-5, 1e-3, 1e-1}) {
    pronk::ode::detail::StageLu lu(a, a_inv);
    REQUIRE(lu.use_structure(sys));
    REQUIRE(lu.compute({&s1, &s2, &s3}, h));
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        m.block(i * n, k * n, n, n).diagonal().setConstant(a_inv(i, k) / h);
      }
    }
    m.block(0, 0, n, n) -= j1;
    m.block(n, n, n, n) -= j2;
    m.block(2 * n, 2 * n, n, n) -= j3;
    Vec r1 = random_vec(n, rng), r2 = random_vec(n, rng), r3 = random_vec(n, rng);
    Vec b(3 * n);
    b << r1, r2, r3;
    lu.solve(r1, r2, r3);
    Vec x(3 * n);
    x << r1, r2, r3;
    const double res = (m * x - b).norm() / (m.norm() * x.norm() + b.norm());
    INFO("h = " << h << ", residual " << res);
    CHECK(res < 1e-14);
  }
  // A position rate that depends on a position: no stage factorisation.
  Eigen::MatrixXd broken = j2;
  broken(0, 6) = 1.0;
  const Eigen::SparseMatrix<double> sb = broken.sparseView();
  pronk::ode::detail::StageLu lu(a, a_inv);
  REQUIRE(lu.use_structure(sys));
  CHECK_FALSE(lu.compute({&s1, &sb, &s3}, 1e-3));
  CHECK(lu.broken());
  CHECK_FALSE(pronk::ode::detail::StageLu(a, a_inv).use_structure(PlainStub(masses)));
}
