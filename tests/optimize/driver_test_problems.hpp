// Analytic test problems and observers for the optimizer driver tests.
#pragma once

#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "optimize/optimizer.hpp"
#include "optimize/problem.hpp"

namespace pronk::optimize::test {

/// A box-bounded problem defined by lambdas.
class LambdaProblem : public Problem {
 public:
  using Fn = std::function<ProblemEvaluation(const std::vector<double>&)>;
  LambdaProblem(std::vector<double> lo, std::vector<double> hi, std::vector<double> x0, int m,
                Fn fn)
      : lo_(std::move(lo)), hi_(std::move(hi)), x0_(std::move(x0)), m_(m), fn_(std::move(fn)) {}
  int dimension() const override { return static_cast<int>(x0_.size()); }
  int num_constraints() const override { return m_; }
  std::vector<double> lower_bounds() const override { return lo_; }
  std::vector<double> upper_bounds() const override { return hi_; }
  std::vector<double> initial_point() const override { return x0_; }
  std::vector<std::string> variable_names() const override {
    std::vector<std::string> v;
    for (int j = 0; j < dimension(); ++j)
      v.push_back(std::string(1, 'p').append(std::to_string(j)));
    return v;
  }
  std::vector<std::string> constraint_names() const override {
    std::vector<std::string> v;
    for (int i = 0; i < m_; ++i) v.push_back(std::string(1, 'c').append(std::to_string(i)));
    return v;
  }
  ProblemEvaluation evaluate(const std::vector<double>& x) const override { return fn_(x); }

  /// Parallel evaluate_batch over `threads` threads (results in input order).
  int threads = 1;
  std::vector<ProblemEvaluation> evaluate_batch(
      const std::vector<std::vector<double>>& xs) const override {
    std::vector<ProblemEvaluation> out(xs.size());
    if (threads <= 1) {
      for (std::size_t i = 0; i < xs.size(); ++i) out[i] = evaluate(xs[i]);
      return out;
    }
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
      pool.emplace_back([&, t] {
        for (std::size_t i = static_cast<std::size_t>(t); i < xs.size();
             i += static_cast<std::size_t>(threads))
          out[i] = evaluate(xs[i]);
      });
    }
    for (auto& th : pool) th.join();
    return out;
  }

 private:
  std::vector<double> lo_, hi_, x0_;
  int m_;
  Fn fn_;
};

/// Centre of the shifted quadratic.
inline const std::vector<double> kCentre = {1.0, -0.5};

inline ProblemEvaluation quadratic_at(const std::vector<double>& x) {
  ProblemEvaluation e;
  e.cost = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const double c = j < kCentre.size() ? kCentre[j] : 0.25;
    e.cost += (x[j] - c) * (x[j] - c);
  }
  return e;
}

/// sum (x_j - c_j)^2 on [-3, 3]^n, minimum 0 at kCentre.
inline LambdaProblem shifted_quadratic(int n = 2) {
  return LambdaProblem(std::vector<double>(static_cast<std::size_t>(n), -3.0),
                       std::vector<double>(static_cast<std::size_t>(n), 3.0),
                       std::vector<double>(static_cast<std::size_t>(n), -2.0), 0, quadratic_at);
}

/// Rosenbrock on [-2, 2]^2 from (-1.2, 1); minimum 0 at (1, 1).
inline LambdaProblem rosenbrock() {
  return LambdaProblem({-2.0, -2.0}, {2.0, 2.0}, {-1.2, 1.0}, 0, [](const std::vector<double>& x) {
    ProblemEvaluation e;
    e.cost = 100.0 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1.0 - x[0], 2);
    return e;
  });
}

/// min x^2 + y^2 s.t. 1 - x - y <= 0 on [-2, 2]^2 from (1.5, 1.5): (0.5, 0.5), cost 0.5.
inline LambdaProblem constrained_circle() {
  return LambdaProblem({-2.0, -2.0}, {2.0, 2.0}, {1.5, 1.5}, 1, [](const std::vector<double>& x) {
    ProblemEvaluation e;
    e.cost = x[0] * x[0] + x[1] * x[1];
    e.constraints = {1.0 - x[0] - x[1]};
    return e;
  });
}

inline double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t j = 0; j < a.size() && j < b.size(); ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(s);
}

/// One observed evaluation.
struct Observed {
  long index;
  std::vector<double> x;
  ProblemEvaluation e;
  std::string purpose;
};

/// Records every evaluation; optionally sets a stop flag after `stop_after`.
class Recorder : public EvaluationObserver {
 public:
  void on_evaluation(long index, const std::vector<double>& x, const ProblemEvaluation& e,
                     const char* purpose) override {
    seen.push_back({index, x, e, purpose});
    if (flag != nullptr && stop_after > 0 && static_cast<long>(seen.size()) >= stop_after)
      flag->store(true);
  }
  std::vector<Observed> seen;
  std::atomic<bool>* flag = nullptr;
  long stop_after = 0;
};

inline OptimizerOptions nlopt_options(const std::string& algorithm, long max_evaluations) {
  OptimizerOptions o;
  o.library = "nlopt";
  o.algorithm = algorithm;
  o.max_evaluations = max_evaluations;
  o.ftol_rel = 0.0;
  o.xtol_rel = 1e-8;
  return o;
}

inline OptimizerOptions ipopt_options() {
  OptimizerOptions o;
  o.library = "ipopt";
  o.max_evaluations = 2000;
  return o;
}

}  // namespace pronk::optimize::test
