// Study 3's full-model stage with each kind of feet (docs/full_model.md#quasi-static-feet): one
// evaluation of the committed tuned design (results/study3_full_model_running/design.json) on
// the stage's 16 trials of 10 s, as the study runs it (the four-mass body, 1 g feet, Verlet
// 1.5e-4 s) and with quasi-static feet on either body (Verlet at 0.7 of their bound, as auto
// picks it, and auto itself). Per setting: the median wall and CPU time of an evaluation over
// `repeats`, the stage's projected time (200 evaluations), the trials stabilized and fallen.
// One JSON document on stdout.
// Usage: bench_study3_feet [repeats] [threads]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/measure.hpp"
#include "bench/bench_clock.hpp"
#include "optimize/staged_study.hpp"

using namespace pronk;

namespace {

struct Setting {
  std::string name;
  std::vector<std::string> overrides;  ///< appended to the study's scene_overrides
  std::vector<double> wall, cpu;
  optimize::Evaluation last;
};

optimize::Study full_stage(const std::vector<std::string>& extra, int threads) {
  const std::string dir = std::string(PRONK_SOURCE_DIR) + "/studies/";
  const std::string file = dir + "study3_full_model_running.json";
  std::ifstream in(file);
  nlohmann::json doc = nlohmann::json::parse(in);
  for (const std::string& o : extra) doc["scene_overrides"].push_back(o);
  std::ifstream recorded(std::string(PRONK_SOURCE_DIR) +
                         "/results/study3_full_model_running/design.json");
  // Every stage's tuned values (the pulse stage's fixed ones and the full stage's).
  const nlohmann::json design = nlohmann::json::parse(recorded);
  std::map<std::string, double> tuned;
  for (const auto& st : design.at("stages")) {
    for (const auto& [k, v] : st.at("parameters").items()) tuned[k] = v.get<double>();
  }
  optimize::Study s = optimize::stage_study(optimize::parse_staged_study(doc, file, dir), 1, tuned);
  s.evaluator.threads = threads;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const int threads = argc > 2 ? std::max(1, std::atoi(argv[2])) : 2;
  const std::string qs = R"(/pseudo_rigid/feet="quasi_static")";
  const std::string auto_method = R"(/pseudo_rigid/solver={"method": "auto"})";
  std::vector<Setting> all = {
      {"four_mass_1g_feet_verlet_1.5e-4 (the study)", {}, {}, {}, {}},
      {"four_mass_quasi_static_verlet_5.7e-4",
       {qs, R"(/pseudo_rigid/solver={"method": "verlet", "h_fixed": 5.7e-4})"},
       {},
       {},
       {}},
      {"four_mass_quasi_static_auto", {qs, auto_method}, {}, {}, {}},
      {"rigid_quasi_static_verlet_6e-4",
       {qs, R"(/pseudo_rigid/body="rigid")",
        R"(/pseudo_rigid/solver={"method": "verlet", "h_fixed": 6e-4})"},
       {},
       {},
       {}},
      {"rigid_quasi_static_auto", {qs, R"(/pseudo_rigid/body="rigid")", auto_method}, {}, {}, {}}};
  for (int k = 0; k < repeats; ++k) {
    for (Setting& s : all) {
      const optimize::Study study = full_stage(s.overrides, threads);
      optimize::Evaluator ev(study.evaluator);
      const double c0 = bench::cpu_seconds();
      const auto w0 = std::chrono::steady_clock::now();
      s.last = ev.evaluate_full(ev.initial_point());
      s.wall.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
      s.cpu.push_back(bench::cpu_seconds() - c0);
    }
  }
  std::printf(
      "{\n  \"benchmark\": \"bench_study3_feet\",\n  \"repeats\": %d,\n  \"threads\": %d,\n"
      "  \"load_average\": %.2f,\n  \"results\": [\n",
      repeats, threads, bench::load_average());
  for (size_t i = 0; i < all.size(); ++i) {
    const Setting& s = all[i];
    int stabilized = 0, fell = 0;
    for (const auto& sc : s.last.scenarios) {
      const auto st = sc.metrics.find("stabilized");
      if (st != sc.metrics.end() && st->second > 0.5) ++stabilized;
      if (sc.status != "completed") ++fell;
    }
    std::printf(
        "    {\"setting\": \"%s\", \"ok\": %s, \"trials\": %zu, \"stabilized\": %d, "
        "\"not_completed\": %d, \"cost\": %.6g, \"evaluation_wall_s_median\": %.4g, "
        "\"evaluation_cpu_s_median\": %.4g, \"stage_200_wall_s\": %.4g}%s\n",
        s.name.c_str(), s.last.ok ? "true" : "false", s.last.scenarios.size(), stabilized, fell,
        s.last.cost, app::bench::median(s.wall), app::bench::median(s.cpu),
        200.0 * app::bench::median(s.wall), i + 1 < all.size() ? "," : "");
  }
  std::printf("  ]\n}\n");
  return 0;
}
