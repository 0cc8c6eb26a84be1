#include "optimize/sensitivity/sobol.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "io/load/input_error.hpp"
#include "optimize/scenario.hpp"

namespace pronk::optimize::sensitivity {

namespace {

constexpr std::uint64_t kBootstrapStream = 0x5a17e11b007ull;

// S1 and ST of every input from rows `idx` of the outputs (column `o`).
struct Estimate {
  std::vector<double> s1, st;
};

Estimate estimate(const std::vector<std::vector<double>>& y, size_t n, size_t k, size_t o,
                  const std::vector<size_t>& idx) {
  const auto a = [&](size_t i) { return y[idx[i]][o]; };
  const auto b = [&](size_t i) { return y[n + idx[i]][o]; };
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < n; ++i) sum += a(i) + b(i);
  const double mean = sum / static_cast<double>(2 * n);
  for (size_t i = 0; i < n; ++i) {
    sum2 += (a(i) - mean) * (a(i) - mean) + (b(i) - mean) * (b(i) - mean);
  }
  const double var = sum2 / static_cast<double>(2 * n);
  Estimate e{std::vector<double>(k, NAN), std::vector<double>(k, NAN)};
  if (!(var > 0.0) || !std::isfinite(var)) return e;
  for (size_t j = 0; j < k; ++j) {
    double first = 0.0, total = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double ab = y[(2 + j) * n + idx[i]][o];
      first += b(i) * (ab - a(i));
      total += (a(i) - ab) * (a(i) - ab);
    }
    e.s1[j] = first / static_cast<double>(n) / var;
    e.st[j] = 0.5 * total / static_cast<double>(n) / var;
  }
  return e;
}

// The q-quantile of finite values (linear interpolation); NaN when there are none.
double quantile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

void bad(const std::string& option, const std::string& expected, double found) {
  throw io::InputError(option, "", expected, std::to_string(found));
}

}  // namespace

void SobolOptions::validate() const {
  if (samples < 2) bad("--samples", "at least 2 base samples", static_cast<double>(samples));
  if (samples > 10000000)
    bad("--samples", "at most 1e7 base samples", static_cast<double>(samples));
  if (bootstrap < 10) bad("--bootstrap", "at least 10 resamples", static_cast<double>(bootstrap));
  if (!(confidence > 0.0 && confidence < 1.0)) bad("--confidence", "a level in (0, 1)", confidence);
}

std::vector<Point> saltelli_points(const std::vector<double>& lower,
                                   const std::vector<double>& upper, const SobolOptions& options) {
  options.validate();
  const size_t k = lower.size(), n = static_cast<size_t>(options.samples);
  if (upper.size() != k) throw std::logic_error("saltelli_points: bounds of different sizes");
  std::vector<Point> pts(n * (k + 2), Point(k, 0.0));
  // Row i of A and of B depends only on (seed, i): more samples extend the same design.
  for (size_t i = 0; i < n; ++i) {
    for (size_t half = 0; half < 2; ++half) {
      SplitMix64 rng(mix_seed(options.seed, 2 * i + half));
      for (size_t j = 0; j < k; ++j) pts[half * n + i][j] = rng.uniform(lower[j], upper[j]);
    }
  }
  for (size_t j = 0; j < k; ++j) {
    for (size_t i = 0; i < n; ++i) {
      Point& p = pts[(2 + j) * n + i];
      p = pts[i];
      p[j] = pts[n + i][j];
    }
  }
  return pts;
}

SobolResult sobol_from_outputs(size_t k, const SobolOptions& options,
                               const std::vector<std::vector<double>>& y) {
  options.validate();
  const size_t n = static_cast<size_t>(options.samples);
  if (y.size() != n * (k + 2)) throw std::logic_error("sobol_from_outputs: wrong output count");
  SobolResult r;
  r.evaluations = static_cast<long>(y.size());
  const size_t m = y.empty() ? 0 : y[0].size();
  std::vector<size_t> identity(n);
  for (size_t i = 0; i < n; ++i) identity[i] = i;
  // The resamples' row indices, shared by every output.
  std::vector<std::vector<size_t>> resamples(static_cast<size_t>(options.bootstrap));
  for (size_t b = 0; b < resamples.size(); ++b) {
    SplitMix64 rng(mix_seed(options.seed ^ kBootstrapStream, b));
    for (size_t i = 0; i < n; ++i) {
      resamples[b].push_back(std::min(n - 1, static_cast<size_t>(rng.uniform() * n)));
    }
  }
  const double alpha = 0.5 * (1.0 - options.confidence);
  for (size_t o = 0; o < m; ++o) {
    SobolIndices s;
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < 2 * n; ++i) sum += y[i][o];
    s.mean = sum / static_cast<double>(2 * n);
    for (size_t i = 0; i < 2 * n; ++i) sum2 += (y[i][o] - s.mean) * (y[i][o] - s.mean);
    s.variance = sum2 / static_cast<double>(2 * n);
    const Estimate e = estimate(y, n, k, o, identity);
    s.s1 = e.s1;
    s.st = e.st;
    std::vector<std::vector<double>> b1(k), bt(k);
    for (const auto& idx : resamples) {
      const Estimate eb = estimate(y, n, k, o, idx);
      for (size_t j = 0; j < k; ++j) {
        b1[j].push_back(eb.s1[j]);
        bt[j].push_back(eb.st[j]);
      }
    }
    for (size_t j = 0; j < k; ++j) {
      const bool ok = std::isfinite(s.s1[j]);
      s.s1_lo.push_back(ok ? quantile(b1[j], alpha) : NAN);
      s.s1_hi.push_back(ok ? quantile(b1[j], 1.0 - alpha) : NAN);
      s.st_lo.push_back(ok ? quantile(bt[j], alpha) : NAN);
      s.st_hi.push_back(ok ? quantile(bt[j], 1.0 - alpha) : NAN);
    }
    r.outputs.push_back(std::move(s));
  }
  return r;
}

SobolResult sobol_indices(const BatchFunction& f, const std::vector<double>& lower,
                          const std::vector<double>& upper, const SobolOptions& options) {
  return sobol_from_outputs(lower.size(), options, f(saltelli_points(lower, upper, options)));
}

}  // namespace pronk::optimize::sensitivity
