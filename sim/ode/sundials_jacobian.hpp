// pronk's Jacobians (Eigen, column-major sparse) handed to SUNDIALS matrices: dense, or
// compressed sparse columns (CSC) on a pattern that only grows, so that KLU's symbolic
// analysis stays valid from one Jacobian to the next. Used by method cvode_bdf
// (sim/ode/cvode.cpp) and by the CVODE peer of `pronk bench` (bench/peers/cvode_peer.cpp).
#pragma once

#include <sundials/sundials_matrix.h>
#include <Eigen/SparseCore>

namespace pronk::ode::sundials {

/// Writes J into the dense SUNMatrix `a` (its other entries zeroed); false when an entry of J
/// is not finite.
bool copy_dense(const Eigen::SparseMatrix<double>& J, SUNMatrix a);

/// The sparsity pattern of a sequence of Jacobians: the union of every pattern seen so far and
/// the diagonal. CVODE forms I - gamma J in place in the matrix it hands the linear solver;
/// with the diagonal stored, that matrix keeps J's pattern, and KLU refactorises it without a
/// new symbolic analysis until an entry appears outside the pattern (a contact that closes).
class SparsePattern {
 public:
  enum class Copy {
    kSame,       ///< J written on the pattern of the previous call
    kGrown,      ///< the pattern grew (or this is the first call): KLU must analyse again
    kNonFinite,  ///< an entry of J is not finite (nothing usable written)
    kFailed      ///< the SUNMatrix could not be reallocated
  };

  /// Writes J (square, compressed or not) into the CSC SUNMatrix `a` on the pattern: the
  /// structure (CVODE's SUNMatZero clears it before every Jacobian) and the values, zeros
  /// where J has no entry.
  Copy copy(const Eigen::SparseMatrix<double>& J, SUNMatrix a);

  /// Stored entries of the pattern (0 before the first copy).
  long nonzeros() const { return static_cast<long>(pattern_.nonZeros()); }

 private:
  /// True when every entry of J lies in the pattern.
  bool contains(const Eigen::SparseMatrix<double>& J) const;

  Eigen::SparseMatrix<double> pattern_;  ///< structure only (compressed); values unused
};

}  // namespace pronk::ode::sundials
