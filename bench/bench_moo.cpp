// Benchmark: NSGA-II with a population of 64, each generation evaluated as one batch by the
// study's Evaluator, on 1 and on 2 threads. The problem is study 3's full-model stage cut to 8
// trials of 2 s (an evaluation costs about 0.4 s of one core) with two objectives, the study's
// cost and the cost of transport; "study2" runs study 2's pulse-model problem instead (16
// trials of 12 s, milliseconds per evaluation). The first population and `generations`
// generations, interleaved repeats after a warm-up, medians and the speed-up; whether both
// thread counts found the same front (they must: evaluations are placed by index); each run's
// process CPU time over its wall time (the cores it really had); the load average before and
// after (the machine may be shared). Prints one JSON object.
// Usage: bench_moo [repeats] [generations] [full|study2]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/measure.hpp"
#include "bench/bench_clock.hpp"
#include "bench/bench_problems.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/pareto/moo_driver.hpp"

using namespace pronk::optimize;
using pronk::app::bench::median;
using pronk::bench::cpu_seconds;
using pronk::bench::load_average;

namespace {

/// The two objectives of an evaluation: the study's cost and the mean cost of transport; a
/// failed evaluation (no valid scene) a large finite penalty, as the driver requires.
std::vector<double> objectives(const Evaluation& e) {
  const auto it = e.aggregated.find("cost_of_transport");
  if (!e.ok || it == e.aggregated.end()) return {1e6, 1e6};
  return {e.cost, std::min(it->second, 1e6)};
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const long generations = argc > 2 ? std::max(1, std::atoi(argv[2])) : 1;
  const bool full = !(argc > 3 && std::string(argv[3]) == "study2");
  const int population = 64;
  const Study st = full ? pronk::bench::full_model_problem("cmaes", population, 1)
                        : pronk::bench::study2_problem("cmaes", population, 1);
  const std::size_t n = st.evaluator.parameters.size();
  pareto::MooOptions o;
  o.algorithm = "nsga2";
  o.population = population;
  o.generations = generations;
  o.seed = 11;
  // One NSGA-II run on `threads` threads: {wall s, cores used}, its result in *r.
  auto run = [&](int threads, pareto::MooResult* r) {
    EvaluatorConfig cfg = st.evaluator;
    cfg.threads = threads;
    const Evaluator ev(cfg);
    const pareto::BatchFunction f = [&](const std::vector<pareto::Point>& xs) {
      std::vector<std::vector<double>> out;
      for (const Evaluation& e : ev.evaluate_full_batch(xs)) out.push_back(objectives(e));
      return out;
    };
    const double c0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    *r = pareto::run(f, std::vector<double>(n, 0.0), std::vector<double>(n, 1.0), 2, o);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::pair<double, double>{wall, (cpu_seconds() - c0) / wall};
  };
  pareto::MooResult r1, r2;
  (void)run(2, &r2);  // warm-up
  const double load_before = load_average();
  std::vector<double> t1, t2, c1, c2;
  for (int k = 0; k < repeats; ++k) {
    const auto [a, ca] = run(1, &r1);
    const auto [b, cb] = run(2, &r2);
    t1.push_back(a);
    t2.push_back(b);
    c1.push_back(ca);
    c2.push_back(cb);
  }
  bool same = r1.front_f == r2.front_f && r1.front_x == r2.front_x &&
              r1.hypervolumes == r2.hypervolumes;
  const nlohmann::json out = {
      {"benchmark", "nsga2_population_batch"},
      {"study", full ? "study3_full_model_running, full-model stage (8 scenarios of 2 s)"
                     : "study2_pagmo_cmaes (study 2's problem)"},
      {"objectives", {"cost", "cost_of_transport"}},
      {"population", population},
      {"generations", generations},
      {"evaluations", r1.evaluations.size()},
      {"batch_calls", r1.batch_calls},
      {"wall_time_1_thread_median_s", median(t1)},
      {"wall_time_2_threads_median_s", median(t2)},
      {"speedup_2_threads", median(t1) / median(t2)},
      {"wall_times_1_thread_s", t1},
      {"wall_times_2_threads_s", t2},
      {"cores_used_1_thread_median", median(c1)},
      {"cores_used_2_threads_median", median(c2)},
      {"same_front", same},
      {"front_size", r1.front_f.size()},
      {"hypervolume_last", r1.hypervolumes.back()},
      {"repeats", repeats},
      {"load_average_1min_before", load_before},
      {"load_average_1min_after", load_average()}};
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
