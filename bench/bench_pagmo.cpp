// Benchmark: a pagmo population of 32 evaluated as one batch, on 1 and 2 threads, on
// study 2's problem (legged pulse model, 16 scenarios of 12 s per evaluation): CMA-ES
// for 8 populations (256 evaluations), interleaved repeats after a warm-up, medians and
// the speed-up, whether both thread counts found the same best cost (they must: the
// evaluations are placed by index), and the load average while it ran (the machine may
// be shared). Prints one JSON object. Usage: bench_pagmo [repeats] [algorithm]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench_suite.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/study.hpp"

using namespace pronk::optimize;
using pronk::app::bench::median;

namespace {

/// The 1-minute load average (/proc/loadavg), or -1 when unreadable.
double load_average() {
  std::ifstream in("/proc/loadavg");
  double one = -1.0;
  in >> one;
  return one;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string algorithm = argc > 2 ? argv[2] : "cmaes";
  const int population = 32, populations = 8;
  const std::string dir = std::string(PRONK_SOURCE_DIR) + "/studies/";
  const Study st =
      load_study(dir + "study2_pagmo_cmaes.json",
                 {"/optimizer/algorithm=" + algorithm,
                  "/optimizer/options={\"population\": " + std::to_string(population) + "}",
                  "/optimizer/max_evaluations=" + std::to_string(population * populations)});
  auto run = [&](int threads) {
    EvaluatorConfig cfg = st.evaluator;
    cfg.threads = threads;
    const Evaluator ev(cfg);
    const auto t0 = std::chrono::steady_clock::now();
    const OptimizerResult r = run_optimizer(ev, st.optimizer);
    return std::make_pair(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), r);
  };
  (void)run(2);  // warm-up (page faults, caches, thread start-up)
  const double load_before = load_average();
  std::vector<double> t1, t2;
  OptimizerResult r1, r2;
  for (int k = 0; k < repeats; ++k) {
    auto [a, ra] = run(1);
    auto [b, rb] = run(2);
    t1.push_back(a);
    t2.push_back(b);
    r1 = ra;
    r2 = rb;
  }
  const nlohmann::json out = {
      {"benchmark", "pagmo_population_batch"},
      {"study", "study2_pagmo_cmaes (study 2's problem)"},
      {"algorithm", algorithm},
      {"population", population},
      {"evaluations", r1.evaluations},
      {"scenarios_per_evaluation", st.evaluator.scenarios.scenarios.size()},
      {"wall_time_1_thread_median_s", median(t1)},
      {"wall_time_2_threads_median_s", median(t2)},
      {"speedup_2_threads", median(t1) / median(t2)},
      {"wall_times_1_thread_s", t1},
      {"wall_times_2_threads_s", t2},
      {"same_best_cost", r1.best_cost == r2.best_cost && r1.best_x == r2.best_x},
      {"best_cost", r1.best_cost},
      {"repeats", repeats},
      {"load_average_1min_before", load_before},
      {"load_average_1min_after", load_average()}};
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
