// Benchmark: study 2 (legged pulse, 16 scenarios) with 300 evaluations, on 1
// and 2 threads, interleaved repeats, medians and the speed-up; plus the share
// of evaluation time spent binding parameters to the scene (impulse model,
// study 1); and one full-model evaluation (study 3's full-model stage, 16 scenarios x
// 10 s) on 1 and 2 threads, with the wall time a 100-evaluation stage would take.
// Prints one JSON object. Usage: bench_study [repeats] [all|full]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/evaluator.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"
#include "io/load/scene_loader.hpp"

using namespace pronk::optimize;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
// One full-model evaluation of study 3's design at its start, 16 scenarios x 10 s.
nlohmann::json full_model_evaluation(const std::string& dir, int repeats) {
  nlohmann::json doc = pronk::io::read_json_file(dir + "study3_full_model_running.json");
  doc["scenarios"]["duration"] = 10;
  doc["scenarios"]["random"]["count"] = 16;
  const StagedStudy st = parse_staged_study(doc, "study3_full_model_running.json", dir);
  std::map<std::string, double> initial;
  for (const auto& p : st.parameters) initial[p.name] = p.initial;
  const Study full = stage_study(st, st.stages.size() - 1, initial);
  std::vector<double> t1, t2;
  double cost1 = 0, cost2 = 0;
  for (int r = 0; r < repeats; ++r) {
    for (int threads : {1, 2}) {
      EvaluatorConfig cfg = full.evaluator;
      cfg.threads = threads;
      const Evaluator ev(cfg);
      const auto t0 = std::chrono::steady_clock::now();
      const Evaluation e = ev.evaluate_full(ev.initial_point());
      (threads == 1 ? t1 : t2)
          .push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      (threads == 1 ? cost1 : cost2) = e.cost;
    }
  }
  return {{"scenarios", 16},
          {"scenario_duration_s", 10},
          {"wall_time_1_thread_median_s", median(t1)},
          {"wall_time_2_threads_median_s", median(t2)},
          {"speedup_2_threads", median(t1) / median(t2)},
          {"stage_100_evaluations_2_threads_min", 100 * median(t2) / 60},
          {"same_cost", cost1 == cost2},
          {"repeats", repeats}};
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const std::string dir = std::string(PRONK_SOURCE_DIR) + "/studies/";
  nlohmann::json out;
  out["benchmark"] = "study_wall_time";
  if (argc > 2 && std::string(argv[2]) == "full") {
    out["full_model_evaluation"] = full_model_evaluation(dir, repeats);
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
  }

  const Study s2 =
      load_study(dir + "study2_legged_pulse_duty50.json", {"/optimizer/max_evaluations=300"});
  std::vector<double> t1, t2;
  long evals = 0;
  {  // warm-up (page faults, caches, thread start-up)
    EvaluatorConfig cfg = s2.evaluator;
    cfg.threads = 2;
    const Evaluator ev(cfg);
    (void)run_optimizer(ev, s2.optimizer);
  }
  double cost1 = 0, cost2 = 0;
  for (int r = 0; r < repeats; ++r) {
    for (int threads : {1, 2}) {
      EvaluatorConfig cfg = s2.evaluator;
      cfg.threads = threads;
      const Evaluator ev(cfg);
      const auto t0 = std::chrono::steady_clock::now();
      const OptimizerResult res = run_optimizer(ev, s2.optimizer);
      const double dt =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      (threads == 1 ? t1 : t2).push_back(dt);
      (threads == 1 ? cost1 : cost2) = res.best_cost;
      evals = res.evaluations;
    }
  }
  out["study2"] = {{"evaluations", evals},
                   {"scenarios", s2.evaluator.scenarios.scenarios.size()},
                   {"wall_time_1_thread_median_s", median(t1)},
                   {"wall_time_2_threads_median_s", median(t2)},
                   {"speedup_2_threads", median(t1) / median(t2)},
                   {"same_best_cost", cost1 == cost2},
                   {"repeats", repeats}};

  // Parameter binding share for the impulse model (study 1).
  const Study s1 = load_study(dir + "study1_body_only_gains.json");
  EvaluatorConfig cfg = s1.evaluator;
  cfg.threads = 1;
  const Evaluator ev(cfg);
  double bind = 0, total = 0;
  SplitMix64 g(7);
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    std::vector<double> x(static_cast<size_t>(ev.dimension()));
    for (double& xi : x) xi = g.uniform();
    const Evaluation e = ev.evaluate_full(x);
    bind += e.binding_time;
    total += e.wall_time;
  }
  out["impulse_parameter_binding"] = {{"evaluations", n},
                                      {"scenarios", s1.evaluator.scenarios.scenarios.size()},
                                      {"mean_evaluation_s", total / n},
                                      {"mean_binding_s", bind / n},
                                      {"binding_share", bind / total}};
  out["full_model_evaluation"] = full_model_evaluation(dir, repeats);
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
