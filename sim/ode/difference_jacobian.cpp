#include "sim/ode/difference_jacobian.hpp"

#include <cmath>
#include <vector>

namespace pronk::ode {

void difference_jacobian(const OdeSystem& sys, double t, const Vec& y,
                         Eigen::SparseMatrix<double>& J) {
  const int n = sys.dimension();
  Vec yp = y, fp(n), fm(n);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int c = 0; c < n; ++c) {
    const double h = 1e-7 * (1.0 + std::abs(y[c]));
    yp[c] = y[c] + h;
    sys.rhs(t, yp, fp);
    yp[c] = y[c] - h;
    sys.rhs(t, yp, fm);
    yp[c] = y[c];
    const double scale = 1.0 / (2.0 * h);
    for (int r = 0; r < n; ++r) {
      const double d = (fp[r] - fm[r]) * scale;
      if (d != 0.0) triplets.emplace_back(r, c, d);
    }
  }
  J.resize(n, n);
  J.setFromTriplets(triplets.begin(), triplets.end());
}

}  // namespace pronk::ode
