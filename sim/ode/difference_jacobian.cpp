#include "sim/ode/difference_jacobian.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace pronk::ode {

void difference_jacobian(const OdeSystem& sys, double t, const Vec& y,
                         Eigen::SparseMatrix<double>& J) {
  const int n = sys.dimension();
  Vec yp = y, f0(n), fp(n);
  sys.rhs(t, y, f0);
  std::vector<Eigen::Triplet<double>> triplets;
  const double step = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int c = 0; c < n; ++c) {
    yp[c] = y[c] + step * (1.0 + std::abs(y[c]));
    const double h = yp[c] - y[c];  // exactly representable
    sys.rhs(t, yp, fp);
    yp[c] = y[c];
    for (int r = 0; r < n; ++r) {
      const double d = (fp[r] - f0[r]) / h;
      if (d != 0.0) triplets.emplace_back(r, c, d);
    }
  }
  J.resize(n, n);
  J.setFromTriplets(triplets.begin(), triplets.end());
}

}  // namespace pronk::ode
