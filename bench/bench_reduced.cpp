// Benchmark: strides per second of the reduced models on one core (Release
// build). Prints one JSON object: per model the median over repeated runs, the
// spread, and the solver work per stride. Usage: bench_reduced [repeats] [strides]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/load/scene_loader.hpp"
#include "sim/reduced/simulator.hpp"

using namespace pronk;

namespace {

struct Case {
  std::string name;
  std::string scene;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 9;
  const long strides = argc > 2 ? std::max(10L, std::atol(argv[2])) : 2000;
  const std::string dir = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/";
  const std::vector<Case> cases = {{"body_only_impulse", "case1_body_only.json"},
                                   {"legged_impulse", "case2_legged_impulse.json"},
                                   {"legged_pulse", "case3_legged_pulse.json"}};
  nlohmann::json out;
  out["benchmark"] = "reduced_strides_per_second";
  out["repeats"] = repeats;
  out["strides_per_run"] = strides;
  out["rtol"] = 1e-9;
  for (const auto& c : cases) {
    scene::Scene s = io::load_scene(dir + c.scene);
    s.simulation.duration = 1e9;
    s.simulation.max_strides = strides;
    s.simulation.solver.rtol = s.simulation.solver.atol = 1e-9;
    const reduced::RunOptions opts{.record_trajectory = false, .record_strides = false};
    std::vector<double> rates;
    reduced::RunResult last;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      last = reduced::simulate(s, opts);
      const double dt =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      rates.push_back(static_cast<double>(strides) / dt);
    }
    const auto [lo, hi] = std::minmax_element(rates.begin(), rates.end());
    const double n = static_cast<double>(strides);
    out["models"][c.name] = {
        {"scene", c.scene},
        {"status", std::string(reduced::to_string(last.status))},
        {"strides_per_second_median", median(rates)},
        {"strides_per_second_min", *lo},
        {"strides_per_second_max", *hi},
        {"steps_per_stride", static_cast<double>(last.cost.solver.steps_accepted) / n},
        {"rhs_evaluations_per_stride", static_cast<double>(last.cost.solver.rhs_evaluations) / n}};
  }
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
