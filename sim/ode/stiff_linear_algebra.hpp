// Linear algebra shared by the implicit steppers (RODAS4, RADAU5): the Jacobian
// df/dy (analytic, or forward differences column by column) and LU factorisations
// of shifted matrices s I - J, dense for small systems and Eigen's SparseLU above
// SolverOptions::dense_lu_max_dimension.
#pragma once

#include <cmath>
#include <complex>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "sim/ode/solver.hpp"

namespace pronk::ode::detail {

/// Writes df/dy at (t, y) into J: the system's analytic Jacobian, or forward differences
/// with f0 = f(t, y) (n extra RHS evaluations, counted). `y_tmp` and `f_tmp` are scratch
/// vectors of size n. Counts one Jacobian evaluation.
inline void evaluate_jacobian(const OdeSystem& sys, double t, const Vec& y, const Vec& f0,
                              Eigen::SparseMatrix<double>& J, Vec& y_tmp, Vec& f_tmp,
                              SolverCounters& counters) {
  const Eigen::Index n = y.size();
  if (sys.has_jacobian()) {
    sys.jacobian(t, y, J);
  } else {
    Eigen::MatrixXd jd(n, n);
    y_tmp = y;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double delta = std::sqrt(1e-16 * std::max(1e-5, std::abs(y[i])));
      y_tmp[i] = y[i] + delta;
      sys.rhs(t, y_tmp, f_tmp);
      jd.col(i) = (f_tmp - f0) / delta;
      y_tmp[i] = y[i];
    }
    counters.rhs_evaluations += n;
    J = jd.sparseView();
  }
  ++counters.jacobian_evaluations;
}

/// LU factorisation of E = s I - J for a real or complex shift s, dense (partial
/// pivoting, pivots checked: it never reports singularity itself) or sparse.
template <typename Scalar>
class ShiftedLu {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  explicit ShiftedLu(bool dense) : dense_(dense) {}

  /// Factorises s I - J; false when singular or non-finite.
  bool compute(const Eigen::SparseMatrix<double>& J, Scalar s) {
    const Eigen::Index n = J.rows();
    ok_ = true;
    if (dense_) {
      e_dense_ = (-Eigen::MatrixXd(J)).template cast<Scalar>();
      e_dense_.diagonal().array() += s;
      lu_dense_.compute(e_dense_);
      const auto& lu = lu_dense_.matrixLU();
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!(std::abs(lu(i, i)) > 0.0) || !std::isfinite(std::abs(lu(i, i)))) ok_ = false;
      }
    } else {
      e_sparse_ = (-J).template cast<Scalar>();
      for (Eigen::Index i = 0; i < n; ++i) e_sparse_.coeffRef(i, i) += s;
      e_sparse_.makeCompressed();
      lu_sparse_.compute(e_sparse_);
      ok_ = lu_sparse_.info() == Eigen::Success;
    }
    return ok_;
  }

  bool ok() const { return ok_; }

  /// Solves E x = b in place.
  void solve(Vector& b) const {
    if (dense_) {
      b = lu_dense_.solve(b);
    } else {
      b = lu_sparse_.solve(b);
    }
  }

 private:
  bool dense_;
  bool ok_ = false;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> e_dense_;
  Eigen::PartialPivLU<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> lu_dense_;
  Eigen::SparseMatrix<Scalar> e_sparse_;
  Eigen::SparseLU<Eigen::SparseMatrix<Scalar>> lu_sparse_;
};

}  // namespace pronk::ode::detail
