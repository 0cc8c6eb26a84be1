#include "optimize/sensitivity/local.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "io/load/input_error.hpp"

namespace pronk::optimize::sensitivity {

namespace {

double step_of(double x, double step) { return x == 0.0 ? step : step * std::abs(x); }

}  // namespace

void LocalOptions::validate() const {
  if (!(std::isfinite(step) && step > 0.0 && step < 1.0)) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%g", step);
    throw io::InputError("--local-step", "", "a relative step in (0, 1), e.g. 1e-2", buf);
  }
}

std::vector<Point> local_points(const std::vector<double>& x0, const LocalOptions& options) {
  std::vector<Point> pts{x0};
  for (size_t j = 0; j < x0.size(); ++j) {
    const double h = step_of(x0[j], options.step);
    for (double d : {h, -h, 0.5 * h, -0.5 * h}) {
      Point p = x0;
      p[j] += d;
      pts.push_back(p);
    }
  }
  return pts;
}

LocalResult local_from_outputs(const std::vector<double>& x0, const LocalOptions& options,
                               const std::vector<std::vector<double>>& y) {
  const size_t k = x0.size();
  if (y.size() != 4 * k + 1) throw std::logic_error("local_from_outputs: wrong output count");
  const std::vector<Point> pts = local_points(x0, options);
  LocalResult r;
  r.x0 = x0;
  r.f0 = y[0];
  r.evaluations = static_cast<long>(y.size());
  const size_t m = r.f0.size();
  r.derivative.assign(m, std::vector<double>(k, 0.0));
  r.error = r.elasticity = r.derivative;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (size_t j = 0; j < k; ++j) {
    const size_t b = 1 + 4 * j;
    // The steps as the points realize them (x0 + h rounds).
    const double h1 = pts[b][j] - pts[b + 1][j], h2 = pts[b + 2][j] - pts[b + 3][j];
    r.h.push_back(0.5 * h1);
    for (size_t i = 0; i < m; ++i) {
      const double d1 = (y[b][i] - y[b + 1][i]) / h1;
      const double d2 = (y[b + 2][i] - y[b + 3][i]) / h2;
      const double d = (4.0 * d2 - d1) / 3.0;
      const double scale = std::max(
          {std::abs(y[b][i]), std::abs(y[b + 1][i]), std::abs(y[b + 2][i]), std::abs(y[b + 3][i])});
      r.derivative[i][j] = d;
      r.error[i][j] = std::abs(d2 - d1) / 3.0 + 4.0 * eps * scale / h2;
      const double f = r.f0[i];
      r.elasticity[i][j] = d == 0.0 ? 0.0 : f == 0.0 ? NAN : x0[j] / f * d;
    }
  }
  return r;
}

LocalResult local_sensitivity(const BatchFunction& f, const std::vector<double>& x0,
                              const LocalOptions& options) {
  options.validate();
  return local_from_outputs(x0, options, f(local_points(x0, options)));
}

}  // namespace pronk::optimize::sensitivity
