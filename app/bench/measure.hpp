// What every benchmark of `pronk bench` shares to measure a setting: thread CPU time, timed
// repeats with their medians, and the cost columns of a row (times and solver counters).
#pragma once

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/ode/solver.hpp"

namespace pronk::app::bench {

/// CPU time of the calling thread [s]: robust against other jobs on a shared machine.
double thread_cpu();

/// Median of v (v non-empty).
double median(std::vector<double> v);

/// A run's result with the median times of its timed repeats.
template <class Result>
struct Timed {
  Result result;        ///< the last repeat's
  double wall_s = 0.0;  ///< median wall time [s]
  double cpu_s = 0.0;   ///< median CPU time of the calling thread [s]
};

/// Calls run() max(1, repeat) times, each timed (thread CPU and wall clock), and stops early
/// after a call for which last(result, its CPU time [s]) is true (a run that failed, or one
/// too costly to repeat).
template <class Run, class Last>
auto timed(int repeat, Run&& run, Last&& last) -> Timed<decltype(run())> {
  Timed<decltype(run())> t;
  std::vector<double> walls, cpus;
  for (int i = 0; i < std::max(1, repeat); ++i) {
    const auto w0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu();
    t.result = run();
    cpus.push_back(thread_cpu() - c0);
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
    if (last(t.result, cpus.back())) break;
  }
  t.wall_s = median(std::move(walls));
  t.cpu_s = median(std::move(cpus));
  return t;
}

/// timed() that always runs `repeat` times.
template <class Run>
auto timed(int repeat, Run&& run) {
  return timed(repeat, std::forward<Run>(run), [](const auto&, double) { return false; });
}

/// What one setting cost: the median times of its timed repeats and its solver's counters.
struct Cost {
  double wall_s = 0.0;  ///< median wall time over the repeats [s]
  double cpu_s = 0.0;   ///< median CPU time of the running thread [s] (robust on a busy machine)
  long steps = 0, rejected = 0, rhs = 0, jacobians = 0, lu = 0;
};

/// The cost of a timed run whose solver counted `c`.
template <class Result>
Cost cost_of(const Timed<Result>& t, const ode::SolverCounters& c) {
  return {t.wall_s,           t.cpu_s,           c.steps_accepted,
          c.steps_rejected,   c.rhs_evaluations, c.jacobian_evaluations,
          c.lu_factorizations};
}

/// A bench.json row's cost columns: wall_s, cpu_s, steps, rejected, rhs, jacobians, lu.
void add_cost(nlohmann::json& row, const Cost& c);

}  // namespace pronk::app::bench
