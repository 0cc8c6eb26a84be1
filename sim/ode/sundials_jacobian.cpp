#include "sim/ode/sundials_jacobian.hpp"

#include <cmath>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

namespace pronk::ode::sundials {

bool copy_dense(const Eigen::SparseMatrix<double>& J, SUNMatrix a) {
  SUNMatZero(a);
  bool finite = true;
  for (int k = 0; k < J.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, k); it; ++it) {
      SM_ELEMENT_D(a, it.row(), it.col()) = it.value();
      finite = finite && std::isfinite(it.value());
    }
  }
  return finite;
}

bool SparsePattern::contains(const Eigen::SparseMatrix<double>& J) const {
  if (pattern_.rows() != J.rows() || pattern_.cols() != J.cols()) return false;
  const int* p_outer = pattern_.outerIndexPtr();
  const int* p_inner = pattern_.innerIndexPtr();
  for (int c = 0; c < J.outerSize(); ++c) {
    int k = p_outer[c];
    const int end = p_outer[c + 1];
    // Inner indices are sorted within a column (Eigen's invariant): one merge walk.
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, c); it; ++it) {
      while (k < end && p_inner[k] < it.row()) ++k;
      if (k == end || p_inner[k] != it.row()) return false;
    }
  }
  return true;
}

SparsePattern::Copy SparsePattern::copy(const Eigen::SparseMatrix<double>& J, SUNMatrix a) {
  const Eigen::Index n = J.rows();
  Copy result = Copy::kSame;
  if (!contains(J)) {
    Eigen::SparseMatrix<double> grown(n, n);
    grown.setIdentity();
    grown = grown + J;  // the union of the structures (values unused)
    if (pattern_.rows() == n && pattern_.cols() == n) grown = grown + pattern_;
    pattern_ = grown;
    pattern_.makeCompressed();
    result = Copy::kGrown;
  }
  const long nnz = nonzeros();
  if (SM_NNZ_S(a) < nnz && SUNSparseMatrix_Reallocate(a, nnz) != 0) return Copy::kFailed;
  const int* p_outer = pattern_.outerIndexPtr();
  const int* p_inner = pattern_.innerIndexPtr();
  sunindextype* ptrs = SM_INDEXPTRS_S(a);
  sunindextype* rows = SM_INDEXVALS_S(a);
  double* data = SM_DATA_S(a);
  for (Eigen::Index c = 0; c <= n; ++c) ptrs[c] = p_outer[c];
  bool finite = true;
  for (int c = 0; c < n; ++c) {
    int k = p_outer[c];
    const int end = p_outer[c + 1];
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, c); it; ++it) {
      while (k < end && p_inner[k] < it.row()) {
        rows[k] = p_inner[k];
        data[k++] = 0.0;
      }
      rows[k] = p_inner[k];  // == it.row(): contains() holds
      data[k++] = it.value();
      finite = finite && std::isfinite(it.value());
    }
    for (; k < end; ++k) {
      rows[k] = p_inner[k];
      data[k] = 0.0;
    }
  }
  return finite ? result : Copy::kNonFinite;
}

}  // namespace pronk::ode::sundials
