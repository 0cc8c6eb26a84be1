// `pronk bench`'s reduced hopper: work-precision of every solver, step and tolerance on the
// legged pulse hopper, the stride map's fixed point per tolerance, and the fitted orders of
// the fixed-step methods.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/bench/suite.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/simulate.hpp"

namespace pronk::app::bench {

using ode::Method;

scene::Scene hopper_scene(const BenchConfig& c, double duration) {
  scene::Scene s = io::load_scene(c.studies_dir + "/scenes/case3_legged_pulse.json");
  s.simulation.duration = duration;
  return s;
}

namespace {

/// A timed hopper run (a failed run is measured once).
using HopperRun = Timed<reduced::RunResult>;

HopperRun run_hopper(const scene::Scene& s, int repeat) {
  return timed(
      repeat, [&] { return simulate(s).run; },
      [](const reduced::RunResult& r, double) {
        return r.status != reduced::RunStatus::kCompleted;
      });
}

WorkPoint hopper_point(const scene::Scene& s, double tol, double h, const HopperRun& run,
                       const reduced::RunResult& ref) {
  WorkPoint p;
  p.problem = "hopper";
  p.solver = std::string(ode::to_string(s.simulation.solver.method));
  p.tol = tol;
  p.h = h;
  p.t_end = s.simulation.duration;
  p.status = std::string(reduced::to_string(run.result.status));
  p.cost = cost_of(run, run.result.cost.solver);
  if (run.result.status != reduced::RunStatus::kCompleted) return p;
  p.errors["final_state"] = (run.result.final_position - ref.final_position).norm();
  const size_t n = std::min(run.result.trajectory.size(), ref.trajectory.size());
  if (n > 0) {
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
      sum += (run.result.trajectory[i].position - ref.trajectory[i].position).squaredNorm();
    }
    p.errors["l2_series"] = std::sqrt(sum / static_cast<double>(n));
  }
  // Touchdown times by stride index; a different stride count is itself an error
  // as large as the run (the stride sequence was not reproduced).
  if (run.result.strides.size() == ref.strides.size()) {
    double worst = 0.0;
    for (size_t i = 0; i < ref.strides.size(); ++i) {
      worst =
          std::max(worst, std::abs(run.result.strides[i].t_touchdown - ref.strides[i].t_touchdown));
    }
    p.errors["touchdown_time"] = worst;
  } else {
    p.errors["touchdown_time"] = p.t_end;
  }
  return p;
}

/// The stride map's periodic orbit per solver tolerance, against a tight reference.
std::vector<WorkPoint> stride_map_points(const BenchConfig& c, double duration) {
  std::vector<WorkPoint> out;
  scene::Scene map_s = hopper_scene(c, duration);
  map_s.simulation.solver.method = Method::kDopri5;
  reduced::StabilityOptions ref_o;
  ref_o.rtol = 1e-12;
  map_s.simulation.solver.rtol = map_s.simulation.solver.atol = ref_o.rtol;
  const reduced::StabilityResult map_ref = reduced::analyze_stability(map_s, ref_o);
  const std::vector<double> map_tols =
      c.quick ? std::vector<double>{1e-5, 1e-8} : std::vector<double>{1e-4, 1e-6, 1e-8, 1e-10};
  for (double tol : map_tols) {
    reduced::StabilityOptions o;
    o.rtol = tol;
    map_s.simulation.solver.rtol = map_s.simulation.solver.atol = tol;
    const Timed<reduced::StabilityResult> run =
        timed(c.repeat, [&] { return reduced::analyze_stability(map_s, o); });
    const reduced::StabilityResult& r = run.result;
    WorkPoint p;
    p.problem = "hopper_stride_map";
    p.solver = "dopri5";
    p.variant = "steps = stride-map evaluations";
    p.tol = tol;
    p.status = r.ok ? "completed" : "failed: " + r.reason;
    p.cost.wall_s = run.wall_s;
    p.cost.cpu_s = run.cpu_s;
    p.cost.steps = r.map_evaluations;
    if (r.ok && map_ref.ok) {
      p.errors["fixed_point"] = (r.fixed_point - map_ref.fixed_point).cwiseAbs().maxCoeff();
      p.errors["spectral_radius"] = std::abs(r.spectral_radius - map_ref.spectral_radius);
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<WorkPoint> hopper_work_precision(const BenchConfig& c) {
  const double duration = c.quick ? 3.0 : 10.0;
  scene::Scene ref_s = hopper_scene(c, duration);
  ref_s.simulation.solver.method = Method::kDopri5;
  ref_s.simulation.solver.rtol = ref_s.simulation.solver.atol = 1e-13;
  const reduced::RunResult ref = simulate(ref_s).run;
  std::vector<WorkPoint> out;
  // The hopper's flights are nearly polynomial in time, so RK4 reaches the
  // reference's accuracy (1e-12 m) already at 2 ms: its steps are 10x larger.
  const std::vector<double> hs = c.quick
                                     ? std::vector<double>{2e-3, 1e-3, 5e-4, 2.5e-4}
                                     : std::vector<double>{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4};
  for (Method method : {Method::kEuler, Method::kRk2, Method::kRk4}) {
    for (double h0 : hs) {
      const double h = method == Method::kRk4 ? 10 * h0 : h0;
      scene::Scene s = ref_s;
      s.simulation.solver.method = method;
      s.simulation.solver.h_fixed = h;
      out.push_back(hopper_point(s, 0.0, h, run_hopper(s, c.repeat), ref));
    }
  }
  const std::vector<double> tols =
      c.quick ? std::vector<double>{1e-3, 1e-5, 1e-7, 1e-9}
              : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  for (double tol : tols) {
    scene::Scene s = ref_s;
    s.simulation.solver.rtol = s.simulation.solver.atol = tol;
    out.push_back(hopper_point(s, tol, 0.0, run_hopper(s, c.repeat), ref));
  }
  const std::vector<WorkPoint> map = stride_map_points(c, duration);
  out.insert(out.end(), map.begin(), map.end());
  return out;
}

std::vector<OrderFit> fit_orders(const std::vector<WorkPoint>& points) {
  std::vector<OrderFit> out;
  for (const char* solver : {"euler", "rk2", "rk4"}) {
    // Least-squares slope of log(error) over log(h) on completed hopper runs whose
    // error is above the reference's own accuracy (1e-11 m).
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (const auto& p : points) {
      if (p.problem != "hopper" || p.solver != solver || p.status != "completed") continue;
      auto it = p.errors.find("final_state");
      if (it == p.errors.end() || it->second < 1e-11) continue;
      const double x = std::log(p.h), y = std::log(it->second);
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
      ++n;
    }
    if (n < 2) continue;
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    out.push_back({"hopper", solver, "final_state", slope, n});
  }
  return out;
}

}  // namespace pronk::app::bench
