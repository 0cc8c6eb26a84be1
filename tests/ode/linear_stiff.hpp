// Test systems shared by the stiff-solver tests (RODAS4, RADAU5).
#pragma once

#include <cmath>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "sim/ode/ode_system.hpp"

namespace pronk::ode::test_systems {

/// y' = A y with A = Q diag(-1, -lambda, -0.5 +- 3i block) Q^T: a stiff linear
/// system with a known solution exp(A t) y0.
class LinearStiff final : public OdeSystem {
 public:
  LinearStiff(double lambda, bool analytic) : analytic_(analytic) {
    Eigen::Matrix4d d = Eigen::Matrix4d::Zero();
    d(0, 0) = -1.0;
    d(1, 1) = -lambda;
    d(2, 2) = -0.5;
    d(2, 3) = 3.0;
    d(3, 2) = -3.0;
    d(3, 3) = -0.5;
    Eigen::Matrix4d q = Eigen::Matrix4d::Random().householderQr().householderQ();
    a_ = q * d * q.transpose();
    d_ = d;
    q_ = q;
  }
  int dimension() const override { return 4; }
  void rhs(double, const Vec& y, Vec& f) const override { f = a_ * y; }
  bool has_jacobian() const override { return analytic_; }
  void jacobian(double, const Vec&, Eigen::SparseMatrix<double>& j) const override {
    j = a_.sparseView();
  }
  bool autonomous() const override { return analytic_; }
  Vec exact(double t, const Vec& y0) const {
    // exp(D t) for the block-diagonal D.
    Eigen::Matrix4d e = Eigen::Matrix4d::Zero();
    e(0, 0) = std::exp(d_(0, 0) * t);
    e(1, 1) = std::exp(d_(1, 1) * t);
    const double r = std::exp(-0.5 * t);
    e(2, 2) = r * std::cos(3 * t);
    e(2, 3) = r * std::sin(3 * t);
    e(3, 2) = -r * std::sin(3 * t);
    e(3, 3) = r * std::cos(3 * t);
    return q_ * e * q_.transpose() * y0;
  }

 private:
  bool analytic_;
  Eigen::Matrix4d a_, d_, q_;
};

}  // namespace pronk::ode::test_systems
