// Benchmark: a pagmo population of 32 evaluated as one batch, on 1 and 2 threads, on
// study 2's problem (legged pulse model, 16 scenarios of 12 s per evaluation; CMA-ES for
// 8 populations, 256 evaluations) or, with problem "full", on study 3's full-model stage
// (the shipped robot in the pseudo-rigid model, 8 scenarios of 2 s per evaluation; 2
// populations, 64 evaluations): interleaved repeats after a warm-up, medians and
// the speed-up, whether both thread counts found the same best cost (they must: the
// evaluations are placed by index), and the load average while it ran (the machine may
// be shared). Beside it, the same 256 points evaluated as 8 batches of 32 straight by the
// Evaluator (no pagmo): the ceiling the machine gives at that moment; and each run's
// process CPU time over its wall time, the cores it really had (a 2-thread run that got
// one core shows 1.0). Prints one JSON object.
// Usage: bench_pagmo [repeats] [algorithm] [study2|full]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/measure.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"
#include "bench/bench_clock.hpp"
#include "bench/bench_problems.hpp"

using namespace pronk::optimize;
using pronk::app::bench::median;
using pronk::bench::cpu_seconds;
using pronk::bench::full_model_problem;
using pronk::bench::load_average;
using pronk::bench::study2_problem;

namespace {

/// Wall and CPU seconds of f().
template <class F>
std::pair<double, double> timed(F&& f) {
  const double c0 = cpu_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  f();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {wall, cpu_seconds() - c0};
}

/// The points a run evaluated, in order.
struct Points final : EvaluationObserver {
  std::vector<std::vector<double>> xs;
  void on_evaluation(long, const std::vector<double>& x, const ProblemEvaluation&,
                     const char*) override {
    xs.push_back(x);
  }
};

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string algorithm = argc > 2 ? argv[2] : "cmaes";
  const bool full = argc > 3 && std::string(argv[3]) == "full";
  const int population = 32, populations = full ? 2 : 8;
  const Study st = full ? full_model_problem(algorithm, population, populations)
                        : study2_problem(algorithm, population, populations);
  // One pagmo run; and the same points as batches of a population straight by the Evaluator.
  auto run = [&](int threads, OptimizerResult* r, Points* seen) {
    EvaluatorConfig cfg = st.evaluator;
    cfg.threads = threads;
    const Evaluator ev(cfg);
    return timed([&] { *r = run_optimizer(ev, st.optimizer, seen); });
  };
  auto batches = [&](int threads, const std::vector<std::vector<double>>& xs) {
    EvaluatorConfig cfg = st.evaluator;
    cfg.threads = threads;
    const Evaluator ev(cfg);
    return timed([&] {
      for (std::size_t i = 0; i < xs.size(); i += population)
        (void)ev.evaluate_batch(
            {xs.begin() + static_cast<long>(i),
             xs.begin() + static_cast<long>(std::min(xs.size(), i + population))});
    });
  };
  OptimizerResult r1, r2;
  Points points;
  (void)run(2, &r2, &points);  // warm-up (page faults, caches, thread start-up); the points
  const double load_before = load_average();
  std::vector<double> t1, t2, c1, c2, e1, e2;
  for (int k = 0; k < repeats; ++k) {
    const auto [a, ca] = run(1, &r1, nullptr);
    const auto [b, cb] = run(2, &r2, nullptr);
    t1.push_back(a);
    t2.push_back(b);
    c1.push_back(ca / a);
    c2.push_back(cb / b);
    e1.push_back(batches(1, points.xs).first);
    e2.push_back(batches(2, points.xs).first);
  }
  const nlohmann::json out = {
      {"benchmark", "pagmo_population_batch"},
      {"study", full ? "study3_full_model_running, full-model stage (8 scenarios of 2 s)"
                     : "study2_pagmo_cmaes (study 2's problem)"},
      {"algorithm", algorithm},
      {"population", population},
      {"evaluations", r1.evaluations},
      {"scenarios_per_evaluation", st.evaluator.scenarios.scenarios.size()},
      {"wall_time_1_thread_median_s", median(t1)},
      {"wall_time_2_threads_median_s", median(t2)},
      {"speedup_2_threads", median(t1) / median(t2)},
      {"wall_times_1_thread_s", t1},
      {"wall_times_2_threads_s", t2},
      {"cores_used_1_thread_median", median(c1)},
      {"cores_used_2_threads_median", median(c2)},
      {"evaluator_only_1_thread_median_s", median(e1)},
      {"evaluator_only_2_threads_median_s", median(e2)},
      {"evaluator_only_speedup_2_threads", median(e1) / median(e2)},
      {"same_best_cost", r1.best_cost == r2.best_cost && r1.best_x == r2.best_x},
      {"best_cost", r1.best_cost},
      {"repeats", repeats},
      {"load_average_1min_before", load_before},
      {"load_average_1min_after", load_average()}};
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
