// Quasi-static feet against the foot masses (docs/full_model.md#quasi-static-feet): a scene
// (pr_running by default) on the rigid body, run with each kind of feet; the reference is the
// foot masses at Verlet 1.5e-5 s. Per setting: median process CPU time
// over `--repeats` interleaved runs, steps, the worst sampled energy balance against the scale,
// and, for the quasi-static feet, the first 10 strides against the reference: the largest
// relative apex difference, the largest touchdown roll or pitch difference and the largest
// relative contact-time difference (first foot down to last foot up; read off the samples when
// the stance hips are locked), and each setting's first
// 10 strides (apex, touchdown roll and pitch, contact time). One JSON document on stdout.
// Usage: bench_quasi_static_feet [scene.json] [--repeats n] [--set /ptr=value ...]
//        [--ref-set /ptr=value ...] [--qs-set /ptr=value ...]
// --set applies to every run; --ref-set to the reference only (e.g. another step);
// --qs-set adds a quasi-static setting (repeatable; each value is one more setting).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/bench/measure.hpp"
#include "bench/bench_clock.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/robot/sampled_contacts.hpp"

using namespace pronk;

namespace {

struct Setting {
  std::string name;
  std::vector<std::string> set;
  std::vector<double> cpu;
  robot::RobotRunResult last;
};

robot::RobotRunResult run(const std::string& path, const std::vector<std::string>& set,
                          double* cpu) {
  const scene::Scene s = io::load_scene(path, set);
  const double c0 = bench::cpu_seconds();
  robot::RobotRunResult r = robot::simulate(s);
  *cpu = bench::cpu_seconds() - c0;
  return r;
}

double worst_balance(const robot::RobotRunResult& r) {
  auto b = [](const robot::RobotSample& s) {
    return s.energies.total() + s.dissipated - s.actuator_work;
  };
  double w = 0.0;
  for (const auto& s : r.samples) w = std::max(w, std::abs(b(s) - b(r.samples.front())));
  return w / r.monitors.energy_scale;
}

struct Agreement {
  size_t strides = 0;
  double apex = 0.0, attitude_deg = 0.0, contact = 0.0;
};

/// Each stride's contact time [s]: the run's own (first foot down to last foot up, at the
/// feet's events) where the stance hips turn; with locked hips the foot masses have no
/// events, so both kinds of feet are read off the samples (robot::sampled_contact_times).
std::vector<double> contact_times(const robot::RobotRunResult& r, bool locked) {
  return locked ? robot::sampled_contact_times(r) : r.stride_contact;
}

Agreement agreement(const robot::RobotRunResult& q, const robot::RobotRunResult& ref, bool locked) {
  Agreement a;
  const std::vector<double> cq = contact_times(q, locked), cr = contact_times(ref, locked);
  a.strides =
      std::min({size_t(10), ref.run.strides.size(), q.run.strides.size(), cr.size(), cq.size()});
  for (size_t k = 0; k < a.strides; ++k) {
    const auto& x = ref.run.strides[k];
    const auto& y = q.run.strides[k];
    a.apex = std::max(a.apex, std::abs(y.apex_height - x.apex_height) / x.apex_height);
    a.attitude_deg = std::max(
        a.attitude_deg, (y.euler123 - x.euler123).head<2>().cwiseAbs().maxCoeff() * 180.0 / M_PI);
    a.contact = std::max(a.contact, std::abs(cq[k] - cr[k]) / cr[k]);
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json";
  std::vector<std::string> common = {R"(/pseudo_rigid/body="rigid")"}, ref_set, qs_sets;
  int repeats = 3;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--set" && a + 1 < argc) {
      common.push_back(argv[++a]);
    } else if (s == "--ref-set" && a + 1 < argc) {
      ref_set.push_back(argv[++a]);
    } else if (s == "--qs-set" && a + 1 < argc) {
      qs_sets.push_back(argv[++a]);
    } else if (s == "--repeats" && a + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++a]));
    } else {
      path = s;
    }
  }
  const bool locked = !io::load_scene(path, common).pseudo_rigid.hip_rotation;
  std::vector<Setting> all;
  // The reference: the foot masses at a step fine enough for their ringing (Verlet 1.5e-5 s:
  // within 0.06 deg and 0.15 % of 7.5e-6 s on pr_running's first 10 strides, where 3e-5 s is
  // still 5 % off in one stride's contact time), unless --ref-set says otherwise.
  std::vector<std::string> ref = common;
  ref.push_back(R"(/pseudo_rigid/solver={"method":"verlet","h_fixed":1.5e-5})");
  ref.insert(ref.end(), ref_set.begin(), ref_set.end());
  all.push_back({"mass_feet_reference", ref, {}, {}});
  all.push_back({"mass_feet_auto", common, {}, {}});
  std::vector<std::string> qs = common;
  qs.push_back(R"(/pseudo_rigid/feet="quasi_static")");
  all.push_back({"quasi_static_auto", qs, {}, {}});
  for (const std::string& extra : qs_sets) {
    std::vector<std::string> v = qs;
    v.push_back(extra);
    all.push_back({"quasi_static " + extra, v, {}, {}});
  }
  for (int k = 0; k < repeats; ++k) {
    for (Setting& s : all) {
      double cpu = 0.0;
      s.last = run(path, s.set, &cpu);
      s.cpu.push_back(cpu);
    }
  }
  std::printf(
      "{\n  \"benchmark\": \"bench_quasi_static_feet\",\n  \"scene\": \"%s\",\n"
      "  \"repeats\": %d,\n  \"load_average\": %.2f,\n  \"results\": [\n",
      path.c_str(), repeats, bench::load_average());
  for (size_t i = 0; i < all.size(); ++i) {
    const Setting& s = all[i];
    std::string name = s.name;
    for (auto p = name.find('"'); p != std::string::npos; p = name.find('"', p + 2)) {
      name.insert(p, "\\");
    }
    const Agreement a = agreement(s.last, all.front().last, locked);
    const std::vector<double> contact = contact_times(s.last, locked);
    const auto& c = s.last.run.cost.solver;
    std::printf(
        "    {\"setting\": \"%s\", \"status\": \"%s\", \"strides\": %zu, \"cpu_s_median\": %.4g, "
        "\"steps\": %ld, \"us_per_step\": %.3g, \"balance_max_of_scale\": %.3g, "
        "\"first_10_strides\": {\"compared\": %zu, \"apex_max_rel\": %.3g, "
        "\"touchdown_attitude_max_deg\": %.3g, \"contact_max_rel\": %.3g},%s\n",
        name.c_str(), std::string(reduced::to_string(s.last.run.status)).c_str(),
        s.last.run.strides.size(), app::bench::median(s.cpu), c.steps_accepted,
        1e6 * app::bench::median(s.cpu) / std::max(1L, c.steps_accepted), worst_balance(s.last),
        a.strides, a.apex, a.attitude_deg, a.contact, "");
    // The first 10 strides themselves: apex [m], touchdown roll and pitch [deg], contact [s].
    std::printf("     \"strides_10\": [");
    for (size_t k = 0; k < a.strides; ++k) {
      const auto& st = s.last.run.strides[k];
      std::printf("%s[%.5f, %.3f, %.3f, %.5f]", k ? ", " : "", st.apex_height,
                  st.euler123.x() * 180.0 / M_PI, st.euler123.y() * 180.0 / M_PI, contact[k]);
    }
    std::printf("]}%s\n", i + 1 < all.size() ? "," : "");
  }
  std::printf("  ]\n}\n");
  return 0;
}
