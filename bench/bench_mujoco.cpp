// pronk's full model against MuJoCo on the same running robot (studies/scenes/pr_running.json,
// 10 s from 10 deg of roll and a 0.2 m offset): the full model's rigid and four-mass bodies on
// "method": "auto" (the rigid body also with quasi-static feet), and "model": "mujoco" (the same
// controller and run loop, MuJoCo stepping the robot's MJCF model) with Euler at 2, 1, 0.5, 0.25
// and 0.125 ms and RK4 at 1 ms. Per setting: median process CPU time over `repeats` interleaved
// runs, MuJoCo's mj_step CPU alone, strides, and the first 10 strides against a refined reference
// (the full model, rigid body, Verlet at 4e-5 s, a third of auto's step): largest relative apex and
// stance-time differences and the largest touchdown-attitude difference. One JSON document on
// stdout. Usage: bench_mujoco [repeats]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/bench/measure.hpp"
#include "bench/bench_clock.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/robot/fidelity.hpp"
#include "sim/simulate.hpp"

using namespace pronk;

namespace {

struct Setting {
  std::string name;
  std::vector<std::string> set;
  std::vector<double> cpu, engine;
  RunResult last;
};

RunResult run(const std::vector<std::string>& set, double* cpu) {
  std::vector<std::string> all = set;
  all.push_back("/simulation/duration=10");
  const scene::Scene s =
      io::load_scene(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json", all);
  RunOptions o;
  o.record_trajectory = false;
  const double c0 = bench::cpu_seconds();
  RunResult r = simulate(s, o);
  *cpu = bench::cpu_seconds() - c0;
  return r;
}

std::vector<Setting> settings() {
  std::vector<Setting> v = {
      {"pronk_rigid_auto", {R"(/pseudo_rigid/body="rigid")"}, {}, {}, {}},
      {"pronk_four_mass_auto", {R"(/pseudo_rigid/body="four_masses")"}, {}, {}, {}},
      {"pronk_rigid_quasi_static_feet_auto",
       {R"(/pseudo_rigid/body="rigid")", R"(/pseudo_rigid/feet="quasi_static")"},
       {},
       {},
       {}},
      {"pronk_rigid_quasi_static_feet_verlet_6e-4",
       {R"(/pseudo_rigid/body="rigid")", R"(/pseudo_rigid/feet="quasi_static")",
        R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":6e-4})"},
       {},
       {},
       {}}};
  for (double dt : {2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4}) {
    char name[48];
    std::snprintf(name, sizeof name, "mujoco_euler_%gms", dt * 1e3);
    v.push_back({name,
                 {R"(/model="mujoco")", "/mujoco={\"timestep\": " + std::to_string(dt) + "}"},
                 {},
                 {},
                 {}});
  }
  v.push_back({"mujoco_rk4_1ms",
               {R"(/model="mujoco")", R"(/mujoco={"timestep": 0.001, "integrator": "rk4"})"},
               {},
               {},
               {}});
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  std::printf("{\n  \"benchmark\": \"bench_mujoco\",\n  \"mujoco_built\": %s,\n",
              scene::mujoco_available() ? "true" : "false");
  if (!scene::mujoco_available()) {
    std::printf("  \"results\": []\n}\n");
    return 0;
  }
  double cpu_ref = 0.0;
  const RunResult ref = run({R"(/pseudo_rigid/body="rigid")",
                             R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":4e-5})"},
                            &cpu_ref);
  std::vector<Setting> all = settings();
  for (int k = 0; k < repeats; ++k) {
    for (Setting& s : all) {
      double cpu = 0.0;
      s.last = run(s.set, &cpu);
      s.cpu.push_back(cpu);
      s.engine.push_back(s.last.engine_cpu);
    }
  }
  std::printf(
      "  \"repeats\": %d,\n  \"reference\": {\"setting\": \"pronk rigid body, verlet "
      "h = 4e-5 s\", \"status\": \"%s\", \"strides\": %zu, \"cpu_s\": %.4g},\n"
      "  \"results\": [\n",
      repeats, std::string(reduced::to_string(ref.run.status)).c_str(), ref.run.strides.size(),
      cpu_ref);
  for (size_t i = 0; i < all.size(); ++i) {
    const Setting& s = all[i];
    const robot::FidelityDiscrepancy d = robot::compare_strides(s.last.run, ref.run, 10);
    std::printf(
        "    {\"setting\": \"%s\", \"status\": \"%s\", \"t_end\": %.4g, \"strides\": %zu, "
        "\"cpu_s_median\": %.4g, \"cpu_s_min\": %.4g, \"mj_step_cpu_s_median\": %.4g, "
        "\"steps\": %ld, \"first_10_strides\": {\"compared\": %ld, \"apex_max_rel\": %.3g, "
        "\"stance_max_rel\": %.3g, \"touchdown_attitude_max_deg\": %.3g}}%s\n",
        s.name.c_str(), std::string(reduced::to_string(s.last.run.status)).c_str(),
        s.last.run.t_end, s.last.run.strides.size(), app::bench::median(s.cpu),
        *std::min_element(s.cpu.begin(), s.cpu.end()), app::bench::median(s.engine),
        s.last.run.cost.solver.steps_accepted, d.strides, d.max_apex_relative,
        d.max_stance_relative, d.max_attitude * 180.0 / M_PI, i + 1 < all.size() ? "," : "");
  }
  std::printf("  ]\n}\n");
  return 0;
}
