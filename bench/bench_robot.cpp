// Benchmarks of the robot in the full model (issue 4). One run each, one JSON
// document on stdout:
//  - drop: the quad spring hopper drop test (1.5 kg body, four 100 N/m prismatic
//    legs, 10 g feet, studies/scenes/case6_pr_drop.json with 10 g feet and a
//    critically damped foot contact with friction mu = 1, as MuJoCo's default
//    contact), 10 s simulated: wall time, steps, RHS and
//    Jacobian counts and the energy-balance error relative to the drop energy,
//    for a few solver tolerances and both error norms. Anchor (measured by the
//    issue's author): MuJoCo 2.2.2, Euler 1 ms, 0.041 s (RK4 0.27 s), losing
//    about 4 % of the drop energy on the first bounce.
//  - ladder: 10 s of running after a moving setpoint from 10 deg roll and a
//    0.4 m lateral offset (studies/scenes/fidelity_duty15.json: pulse legs as
//    forces at ghost-point hips, 15 % duty) at each fidelity.
//  - running (issue 18): studies/scenes/pr_running.json, 10 s simulated, on RODAS4 (the
//    scene's tolerances) and on Verlet (h_fixed 1.5e-4 s): process CPU
//    time, median of `repeats` runs each (interleaved), the worst sampled energy balance
//    relative to the energy scale, and the RODAS4 / Verlet CPU ratio; the same with the body
//    as one rigid body ("pseudo_rigid": {"body": "rigid"}), its CPU relative to the four-mass
//    body's and its strides against them (largest apex and touchdown-attitude differences).
// Usage: bench_robot [repeats [groups]]; groups is "all" (default), "running" or
// "running_verlet" (the Verlet rows of "running" alone, for profiling).
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/load/scene_loader.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/robot/fidelity.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/simulate.hpp"

using namespace pronk;

namespace {

std::string scene_path(const char* name) {
  return std::string(PRONK_SOURCE_DIR) + "/studies/scenes/" + name;
}

void drop(double tol, bool body_norm, bool* first) {
  scene::Scene s = io::load_scene(scene_path("case6_pr_drop.json"));
  s.pseudo_rigid.foot_mass = 0.01;
  s.pseudo_rigid.contact_damping = 63.0;  // 2 sqrt(k m): plastic foot impact
  s.pseudo_rigid.friction = 1.0;          // MuJoCo's default: without it the body tips over
  s.pseudo_rigid.solver_auto = false;     // RODAS4 at tol (the method the bench measures)
  s.pseudo_rigid.solver.rtol = tol;
  s.pseudo_rigid.solver.atol = tol;
  s.pseudo_rigid.body_error_norm = body_norm;
  s.simulation.duration = 10.0;
  const robot::RobotRunResult r = robot::simulate(s, {false});
  const double mass = s.body.mass + 4 * s.pseudo_rigid.foot_mass;
  const double drop_energy = mass * s.gravity * (s.initial.position.z() - s.legs.length);
  const auto& c = r.run.cost.solver;
  double first_apex = 0.0, last_apex = 0.0;
  for (const auto& st : r.run.strides) {
    if (!st.has_apex) continue;
    if (first_apex == 0.0) first_apex = st.apex_height;
    last_apex = st.apex_height;
  }
  std::printf(
      "%s    {\"group\": \"drop\", \"tol\": %g, \"norm\": \"%s\", \"status\": \"%s\", "
      "\"wall_s\": %.4g, \"steps\": %ld, \"rejected\": %ld, \"rhs\": %ld, \"jacobians\": %ld, "
      "\"lu\": %ld, \"energy_error_rel_drop\": %.3g, \"hops\": %zu, \"first_apex_m\": %.5f, "
      "\"last_apex_m\": %.5f, \"mujoco_euler_1ms_anchor_s\": 0.041}",
      *first ? "" : ",\n", tol, body_norm ? "body" : "state",
      std::string(reduced::to_string(r.run.status)).c_str(), r.run.cost.wall_time, c.steps_accepted,
      c.steps_rejected, c.rhs_evaluations, c.jacobian_evaluations, c.lu_factorizations,
      r.monitors.energy_drift / drop_energy, r.run.strides.size(), first_apex, last_apex);
  std::fflush(stdout);
  *first = false;
}

void ladder(scene::ModelKind model, bool* first) {
  scene::Scene s = io::load_scene(scene_path("fidelity_duty15.json"));
  s.model = model;
  s.simulation.duration = 10.0;
  reduced::RunResult run;
  pronk::RunOptions o;
  o.record_trajectory = false;
  run = pronk::simulate(s, o).run;
  const auto& c = run.cost.solver;
  std::printf(
      "%s    {\"group\": \"ladder\", \"model\": \"%s\", \"status\": \"%s\", \"t_end\": %.4g, "
      "\"wall_s\": %.4g, \"steps\": %ld, \"rhs\": %ld, \"jacobians\": %ld, \"strides\": %zu}",
      *first ? "" : ",\n", std::string(scene::to_string(model)).c_str(),
      std::string(reduced::to_string(run.status)).c_str(), run.t_end, run.cost.wall_time,
      c.steps_accepted, c.rhs_evaluations, c.jacobian_evaluations, run.strides.size());
  std::fflush(stdout);
  *first = false;
}

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// pr_running for 10 s on RODAS4 (the scene's settings) and on Verlet, `repeats` interleaved
/// runs each: median CPU time, and the ratio.
void running(int repeats, bool verlet_only, bool* first) {
  struct Setting {
    const char* name;
    std::vector<std::string> set;
    std::vector<double> cpu;
    robot::RobotRunResult last;
  };
  std::vector<Setting> settings = {
      {"rodas4", {R"(/pseudo_rigid/solver={"method":"rodas4"})"}, {}, {}},
      {"verlet",
       {R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-4,"energy_tol":1e-5})"},
       {},
       {}},
      {"rodas4_rigid",
       {R"(/pseudo_rigid/solver={"method":"rodas4"})", R"(/pseudo_rigid/body="rigid")"},
       {},
       {}},
      {"verlet_rigid",
       {R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-4,"energy_tol":1e-5})",
        R"(/pseudo_rigid/body="rigid")"},
       {},
       {}}};
  if (verlet_only) settings = {settings[1], settings[3]};
  for (int k = 0; k < repeats; ++k) {
    for (Setting& st : settings) {
      std::vector<std::string> set = st.set;
      set.push_back("/simulation/duration=10");
      const scene::Scene s = io::load_scene(scene_path("pr_running.json"), set);
      const double c0 = cpu_seconds();
      st.last = robot::simulate(s, {true});
      st.cpu.push_back(cpu_seconds() - c0);
    }
  }
  for (const Setting& st : settings) {
    const robot::RobotRunResult& r = st.last;
    double worst = 0.0;  // worst sampled |balance - balance(0)|
    auto balance = [](const robot::RobotSample& x) {
      return x.energies.total() + x.dissipated - x.actuator_work;
    };
    for (const auto& x : r.samples) {
      worst = std::max(worst, std::abs(balance(x) - balance(r.samples.front())));
    }
    const auto& c = r.run.cost.solver;
    std::printf(
        "%s    {\"group\": \"running\", \"method\": \"%s\", \"status\": \"%s\", "
        "\"t_end\": %.4g, \"repeats\": %d, \"cpu_s_median\": %.4g, \"cpu_s_min\": %.4g, "
        "\"cpu_s_max\": %.4g, \"steps\": %ld, \"rejected\": %ld, \"rhs\": %ld, "
        "\"jacobians\": %ld, \"strides\": %zu, \"worst_sample_balance_rel\": %.3g, "
        "\"energy_drift_rel\": %.3g}",
        *first ? "" : ",\n", st.name, std::string(reduced::to_string(r.run.status)).c_str(),
        r.run.t_end, repeats, median(st.cpu), *std::min_element(st.cpu.begin(), st.cpu.end()),
        *std::max_element(st.cpu.begin(), st.cpu.end()), c.steps_accepted, c.steps_rejected,
        c.rhs_evaluations, c.jacobian_evaluations, r.run.strides.size(),
        worst / r.monitors.energy_scale, r.monitors.energy_drift / r.monitors.energy_scale);
    *first = false;
  }
  if (verlet_only) {
    std::fflush(stdout);
    return;
  }
  std::printf(",\n    {\"group\": \"running\", \"rodas4_over_verlet_cpu\": %.4g}",
              median(settings[0].cpu) / median(settings[1].cpu));
  for (int k = 0; k < 2; ++k) {
    const robot::FidelityDiscrepancy d =
        robot::compare_strides(settings[k].last.run, settings[k + 2].last.run);
    std::printf(
        ",\n    {\"group\": \"running\", \"method\": \"%s\", "
        "\"rigid_over_four_mass_cpu\": %.4g, \"rigid_cpu_per_10_s\": %.4g, "
        "\"four_mass_cpu_per_10_s\": %.4g, \"strides_compared\": %ld, "
        "\"apex_max_diff_m\": %.3g, \"touchdown_attitude_max_diff_deg\": %.3g}",
        settings[k].name, median(settings[k + 2].cpu) / median(settings[k].cpu),
        median(settings[k + 2].cpu) * 10.0 / settings[k + 2].last.run.t_end,
        median(settings[k].cpu) * 10.0 / settings[k].last.run.t_end, d.strides, d.max_apex,
        d.max_attitude * 180.0 / M_PI);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const bool all = argc <= 2 || std::string(argv[2]) == "all";
  std::printf("{\n  \"benchmark\": \"bench_robot\",\n  \"results\": [\n");
  bool first = true;
  if (all) {
    for (double tol : {1e-4, 1e-5, 1e-6}) drop(tol, true, &first);
    drop(1e-4, false, &first);
    for (auto m :
         {scene::ModelKind::kImpulse, scene::ModelKind::kPulse, scene::ModelKind::kPseudoRigid}) {
      ladder(m, &first);
    }
  }
  running(repeats, argc > 2 && std::string(argv[2]) == "running_verlet", &first);
  std::printf("\n  ]\n}\n");
  return 0;
}
