#include "app/bench_suite.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>

#include "optimize/map/map_engine.hpp"
#include "optimize/map/map_study.hpp"
#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/reduced/stride_fit.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/simulate.hpp"
// The satellite scene is shared by the tests, bench_pseudorigid and this bench.
#include "tests/pseudorigid/scenes.hpp"

namespace pronk::app::bench {

/// CPU time of the calling thread [s]: robust against other jobs on a shared machine.
double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

namespace pr = pronk::pseudorigid;
using ode::Method;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void set_cost(WorkPoint& p, const ode::SolverCounters& c) {
  p.steps = c.steps_accepted;
  p.rejected = c.steps_rejected;
  p.rhs = c.rhs_evaluations;
  p.jacobians = c.jacobian_evaluations;
  p.lu = c.lu_factorizations;
}

// ---------------------------------------------------------------- satellite

constexpr double kSatelliteEnd = 20.0;  // [s], Ridgely 2001, §4.4.1 / issue 3

struct SatelliteRun {
  pr::RunSummary summary;
  double wall = 0.0;  // median [s]
  double cpu = 0.0;   // median [s]
};

pr::Mechanism satellite(double k, Method method, double tol, double h, pr::ErrorNorm norm) {
  pr::Mechanism m = pr::test_scenes::satellite(k, kSatelliteEnd);
  m.simulation.solver.method = method;
  m.simulation.solver.rtol = m.simulation.solver.atol = tol > 0 ? tol : 1e-6;
  if (h > 0) m.simulation.solver.h_fixed = h;
  m.simulation.error_norm = norm;
  return m;
}

SatelliteRun run_satellite(const pr::Mechanism& m, int repeat) {
  SatelliteRun r;
  std::vector<double> walls, cpus;
  for (int i = 0; i < repeat; ++i) {
    const double c0 = thread_cpu();
    r.summary = pr::simulate(m);
    cpus.push_back(thread_cpu() - c0);
    walls.push_back(r.summary.wall_time);
    // A diverged explicit run is measured once: its cost is not the point.
    if (r.summary.status != pr::RunStatus::kCompleted) break;
  }
  r.wall = median(walls);
  r.cpu = median(cpus);
  return r;
}

/// World angular velocity series of the satellite run [rad/s].
std::vector<Eigen::Vector3d> omega_series(const pr::Mechanism& m, const pr::RunSummary& r) {
  const pr::MechanismSystem sys(m);
  std::vector<Eigen::Vector3d> w;
  w.reserve(r.y.size());
  for (const auto& y : r.y) w.push_back(sys.body_omega(0, y));
  return w;
}

/// The satellite point with its errors against the analytic solution and `ref`.
WorkPoint satellite_point(const std::string& problem, const pr::Mechanism& m,
                          const std::string& variant, double k, double tol, double h,
                          const SatelliteRun& run, const pr::RunSummary* ref,
                          const std::vector<Eigen::Vector3d>* ref_omega) {
  WorkPoint p;
  p.problem = problem;
  p.solver = std::string(ode::to_string(m.simulation.solver.method));
  p.variant = variant;
  p.stiffness = k;
  p.tol = tol;
  p.h = h;
  p.t_end = m.simulation.t_end;
  p.status = std::string(pr::to_string(run.summary.status));
  p.wall_s = run.wall;
  p.cpu_s = run.cpu;
  set_cost(p, run.summary.counters);
  if (run.summary.status != pr::RunStatus::kCompleted) return p;
  const auto w = omega_series(m, run.summary);
  const double w0 = pr::test_scenes::satellite_omega(0.0).norm();
  p.errors["omega_final"] =
      (w.back() - pr::test_scenes::satellite_omega(run.summary.t.back())).norm() / w0;
  if (ref != nullptr && ref->y.size() == run.summary.y.size()) {
    p.errors["omega_final_ref"] = (w.back() - ref_omega->back()).norm() / w0;
    double s = 0.0;
    for (size_t i = 0; i < w.size(); ++i) s += ((w[i] - (*ref_omega)[i]) / w0).squaredNorm();
    p.errors["omega_l2"] = std::sqrt(s / static_cast<double>(w.size()));
    const Eigen::VectorXd d = run.summary.y.back() - ref->y.back();
    p.errors["final_state"] = d.norm() / std::sqrt(static_cast<double>(d.size()));
  }
  return p;
}

/// Tight reference solution of the satellite at stiffness k (RODAS4, per-state norm).
pr::RunSummary satellite_reference(double k) {
  return pr::simulate(satellite(k, Method::kRodas4, 1e-11, 0.0, pr::ErrorNorm::kState));
}

/// The stiffness sweep's reference at k: RADAU5 at tol 1e-10 (RODAS4 at 1e-11 would take
/// minutes at 1e8 N/m); its omega error against the analytic precession is the model's error.
struct SweepReference {
  pr::Mechanism m;
  pr::RunSummary run;
  std::vector<Eigen::Vector3d> omega;
  double model_error = 0.0;
};

SweepReference sweep_reference(double k) {
  SweepReference r;
  r.m = satellite(k, Method::kRadau5, 1e-10, 0.0, pr::ErrorNorm::kState);
  r.run = pr::simulate(r.m);
  r.omega = omega_series(r.m, r.run);
  if (!r.omega.empty()) {
    r.model_error = (r.omega.back() - pr::test_scenes::satellite_omega(r.run.t.back())).norm() /
                    pr::test_scenes::satellite_omega(0.0).norm();
  }
  return r;
}

// ---------------------------------------------------------------- hopper

scene::Scene hopper_scene(const BenchConfig& c, double duration) {
  scene::Scene s = io::load_scene(c.studies_dir + "/scenes/case3_legged_pulse.json");
  s.simulation.duration = duration;
  return s;
}

struct HopperRun {
  reduced::RunResult result;
  double wall = 0.0, cpu = 0.0;  // medians [s]
};

HopperRun run_hopper(const scene::Scene& s, int repeat) {
  HopperRun r;
  std::vector<double> walls, cpus;
  for (int i = 0; i < repeat; ++i) {
    const double c0 = thread_cpu();
    r.result = simulate(s).run;
    cpus.push_back(thread_cpu() - c0);
    walls.push_back(r.result.cost.wall_time);
    if (r.result.status != reduced::RunStatus::kCompleted) break;
  }
  r.wall = median(walls);
  r.cpu = median(cpus);
  return r;
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
  p.wall_s = run.wall;
  p.cpu_s = run.cpu;
  set_cost(p, run.result.cost.solver);
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

}  // namespace

// ---------------------------------------------------------------- public groups

std::vector<WorkPoint> satellite_work_precision(const BenchConfig& c) {
  const double k = 1e6;
  const pr::Mechanism ref_m = satellite(k, Method::kRodas4, 1e-11, 0.0, pr::ErrorNorm::kState);
  const pr::RunSummary ref = satellite_reference(k);
  const auto ref_omega = omega_series(ref_m, ref);
  std::vector<WorkPoint> out;
  const std::vector<double> tols =
      c.quick ? std::vector<double>{1e-3, 1e-5, 1e-7}
              : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  for (double tol : tols) {
    for (auto norm : {pr::ErrorNorm::kState, pr::ErrorNorm::kBody}) {
      const pr::Mechanism m = satellite(k, Method::kRodas4, tol, 0.0, norm);
      out.push_back(satellite_point("satellite", m, norm == pr::ErrorNorm::kBody ? "body" : "state",
                                    k, tol, 0.0, run_satellite(m, c.repeat), &ref, &ref_omega));
    }
    // DOPRI5 is stability-limited here: its cost hardly depends on the tolerance.
    if (!c.quick || tol <= 1e-5) {
      const pr::Mechanism m = satellite(k, Method::kDopri5, tol, 0.0, pr::ErrorNorm::kState);
      out.push_back(satellite_point("satellite", m, "state", k, tol, 0.0,
                                    run_satellite(m, c.repeat), &ref, &ref_omega));
    }
  }
  // RADAU5 (a Jacobian per stage once the shared one fails) and pronk's CVODE backend (KLU).
  const std::vector<double> radau_tols =
      c.quick ? std::vector<double>{1e-6} : std::vector<double>{1e-5, 1e-6, 1e-7, 1e-8};
  for (double tol : radau_tols) {
    const pr::Mechanism m = satellite(k, Method::kRadau5, tol, 0.0, pr::ErrorNorm::kState);
    out.push_back(satellite_point("satellite", m, "state", k, tol, 0.0, run_satellite(m, c.repeat),
                                  &ref, &ref_omega));
  }
  const std::vector<double> cvode_tols =
      c.quick ? std::vector<double>{1e-7} : std::vector<double>{1e-6, 1e-7, 1e-8};
  for (double tol : cvode_tols) {
    const pr::Mechanism m = satellite(k, Method::kCvodeBdf, tol, 0.0, pr::ErrorNorm::kState);
    out.push_back(satellite_point("satellite", m, "klu", k, tol, 0.0, run_satellite(m, c.repeat),
                                  &ref, &ref_omega));
  }
  // Fixed-step explicit methods: RK4 is stable below h ~ 2.8 / omega_max (about
  // 1e-3 s here); Euler and RK2 are unstable for undamped vibration at any step and
  // must end with a divergence status (Ridgely 2001, §3.5.1, fig. 3.4), which is what they show.
  const std::vector<double> hs =
      c.quick ? std::vector<double>{1e-3, 5e-4} : std::vector<double>{1e-3, 5e-4, 2.5e-4};
  for (Method method : {Method::kEuler, Method::kRk2, Method::kRk4}) {
    for (double h : hs) {
      const pr::Mechanism m = satellite(k, method, 0.0, h, pr::ErrorNorm::kState);
      out.push_back(satellite_point("satellite", m, "state", k, 0.0, h, run_satellite(m, c.repeat),
                                    &ref, &ref_omega));
    }
  }
  // Velocity Verlet: symplectic, one RHS per step, stable below h = 2 / omega_max (~1e-3 s
  // here); its energy error stays bounded, so the rigid motion is what its error measures.
  const std::vector<double> hv =
      c.quick ? std::vector<double>{8e-4, 2.5e-4} : std::vector<double>{8e-4, 5e-4, 2.5e-4, 1e-4};
  for (double h : hv) {
    const pr::Mechanism m = satellite(k, Method::kVerlet, 0.0, h, pr::ErrorNorm::kState);
    out.push_back(satellite_point("satellite", m, "state", k, 0.0, h, run_satellite(m, c.repeat),
                                  &ref, &ref_omega));
  }
  return out;
}

std::vector<WorkPoint> satellite_stiffness_sweep(const BenchConfig& c) {
  std::vector<WorkPoint> out;
  const std::vector<double> ks =
      c.quick ? std::vector<double>{1e4, 1e8} : std::vector<double>{1e4, 1e5, 1e6, 1e7, 1e8};
  const double tol = 1e-6;
  for (double k : ks) {
    const SweepReference ref = sweep_reference(k);
    auto point = [&](const pr::Mechanism& m, const std::string& variant, double t, double h,
                     int repeat) {
      WorkPoint p = satellite_point("satellite_stiffness", m, variant, k, t, h,
                                    run_satellite(m, repeat), &ref.run, &ref.omega);
      p.errors["model_omega_error"] = ref.model_error;
      out.push_back(std::move(p));
    };
    for (auto norm : {pr::ErrorNorm::kState, pr::ErrorNorm::kBody}) {
      point(satellite(k, Method::kRodas4, tol, 0.0, norm),
            norm == pr::ErrorNorm::kBody ? "body" : "state", tol, 0.0, c.repeat);
    }
    // DOPRI5 resolves the internal vibration: its cost grows like sqrt(k).
    if (!c.quick || k <= 1e6) {
      point(satellite(k, Method::kDopri5, tol, 0.0, pr::ErrorNorm::kState), "state", tol, 0.0,
            c.quick ? 1 : c.repeat);
    }
    // RADAU5 over tolerances (its tolerance maps to 0.1 tol^(2/3)): the headline takes the
    // cheapest within the omega error target at each stiffness. Once its shared-Jacobian
    // Newton fails it takes a Jacobian per stage and steps over the vibration.
    const std::vector<double> radau_tols =
        c.quick ? std::vector<double>{1e-6, 1e-8}
                : std::vector<double>{1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8};
    for (double t : radau_tols) {
      point(satellite(k, Method::kRadau5, t, 0.0, pr::ErrorNorm::kState), "state", t, 0.0,
            c.quick ? 1 : c.repeat);
    }
    // Verlet at half its stability limit, h = 1 / omega_max ~ 5e-4 s sqrt(1e6 / k): sqrt(k)
    // growth, but one cheap RHS per step.
    const double h = 5e-4 * std::sqrt(1e6 / k);
    point(satellite(k, Method::kVerlet, 0.0, h, pr::ErrorNorm::kState), "state", 0.0, h,
          c.quick ? 1 : c.repeat);
  }
  return out;
}

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
  // The stride map's periodic orbit (sim/simulate.hpp) per solver tolerance.
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
    std::vector<double> walls, cpus;
    reduced::StabilityResult r;
    for (int i = 0; i < c.repeat; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = thread_cpu();
      r = reduced::analyze_stability(map_s, o);
      cpus.push_back(thread_cpu() - c0);
      walls.push_back(seconds_since(t0));
    }
    WorkPoint p;
    p.problem = "hopper_stride_map";
    p.solver = "dopri5";
    p.variant = "steps = stride-map evaluations";
    p.tol = tol;
    p.status = r.ok ? "completed" : "failed: " + r.reason;
    p.wall_s = median(walls);
    p.cpu_s = median(cpus);
    p.steps = r.map_evaluations;
    if (r.ok && map_ref.ok) {
      p.errors["fixed_point"] = (r.fixed_point - map_ref.fixed_point).cwiseAbs().maxCoeff();
      p.errors["spectral_radius"] = std::abs(r.spectral_radius - map_ref.spectral_radius);
    }
    out.push_back(p);
  }
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

// ---------------------------------------------------------------- fidelity ladder

namespace {

// A run in the scene's model, records only (the stride-map fit's simulator).
reduced::RunResult simulate_records(const scene::Scene& s) {
  RunOptions o;
  o.record_trajectory = false;
  return simulate(s, o).run;
}

void set_fit(FidelityPoint& p, const reduced::StrideFitResult& f) {
  p.spectral_radius_fit = f.spectral_radius;
  p.fit_ok = f.ok;
  p.fit_residual_rel = f.residual_rel;
  if (!f.ok) p.note += std::string(p.note.empty() ? "" : "; ") + "no stride-map fit: " + f.reason;
}

/// The full model's settings of every pseudo-rigid run of the ladder (see full_model_rung).
constexpr const char* kFullModelSettings = R"({"legs": "force", "internal_stiffness": 1e6})";

/// What a rung's run was: the model simulate() ran and its solver's counters.
void set_ran(FidelityPoint& p, const RunResult& r) {
  p.ran_model = std::string(scene::to_string(r.model));
  p.rhs_evaluations = r.run.cost.solver.rhs_evaluations;
  p.jacobians = r.run.cost.solver.jacobian_evaluations;
}

FidelityPoint reduced_rung(const scene::Scene& s, const BenchConfig& c) {
  FidelityPoint p;
  p.model = std::string(scene::to_string(s.model));
  p.pulse_duration = s.model == scene::ModelKind::kPulse ? s.pulse.duration : 0.0;
  p.t_end = s.simulation.duration;
  std::vector<double> walls, cpus;
  RunResult full;
  RunOptions opts;
  opts.record_trajectory = false;
  for (int i = 0; i < c.repeat; ++i) {
    const double c0 = thread_cpu();
    full = simulate(s, opts);
    cpus.push_back(thread_cpu() - c0);
    walls.push_back(full.run.cost.wall_time);
  }
  const reduced::RunResult& r = full.run;
  set_ran(p, full);
  p.status = std::string(reduced::to_string(r.status));
  p.wall_s = median(walls);
  p.cpu_s = median(cpus);
  p.cost_per_sim_s = p.cpu_s / std::max(r.t_end, 1e-9);
  p.strides = static_cast<long>(r.strides.size());
  double duty = 0, apex = 0;
  int nd = 0, na = 0;
  for (size_t i = 1; i < r.strides.size(); ++i) {
    if (r.strides[i].duty_cycle > 0) {
      duty += r.strides[i].duty_cycle;
      ++nd;
    }
    if (r.strides[i].has_apex) {
      apex += r.strides[i].apex_height;
      p.apexes.push_back(r.strides[i].apex_height);
      ++na;
    }
  }
  p.mean_duty = nd ? duty / nd : 0.0;
  p.mean_apex = na ? apex / na : 0.0;
  const reduced::StabilityResult st = reduced::analyze_stability(s);
  p.spectral_radius = st.spectral_radius;
  p.spectral_radius_method = "stride_map";
  p.stable = st.ok && st.spectral_radius < 1.0;
  if (!st.ok) p.note = "no periodic orbit: " + st.reason;
  // The estimator the pseudo-rigid rung relies on, checked here against the stride map.
  set_fit(p, reduced::estimate_stride_map(s, simulate_records));
  return p;
}

/// The same robot in the full model with force legs (Ridgely 2001, §2.7: leg forces at ghost-point
/// hips, no leg masses) and internal springs of 1e6 N/m, so that all three rungs share massless
/// legs and differ only in the body model and the stance dynamics. One run per point (seconds per
/// simulated second); skipped with --quick. Stability: the spectral radius of the stride map
/// fitted to 4 small-perturbation runs of 6 s (the full model has no stride map to evaluate);
/// verdict: the run completes without a fall and that radius is below 1.
/// rigid: the same with the body as one rigid body (the "rigid" rung: same legs and control,
/// no internal springs).
FidelityPoint full_model_rung(const scene::Scene& s, const BenchConfig& c, bool rigid) {
  FidelityPoint p;
  p.model = rigid ? "rigid" : "pseudo_rigid";
  p.pulse_duration = s.pulse.duration;
  p.t_end = s.simulation.duration;
  if (c.quick) {
    p.available = false;
    p.status = "skipped";
    p.note = "not run with --quick: the full model costs seconds per simulated second";
    return p;
  }
  scene::Scene sp = s;
  sp.model = scene::ModelKind::kPseudoRigid;  // (simulate() runs the scene's model)
  sp.pseudo_rigid.legs = scene::PseudoRigid::Legs::kForce;
  // Internal springs of 1e6 N/m: at the scene's 1e5 N/m the 50 ms pulses strain the body
  // by several per cent and it falls after three strides where the rigid models run on
  // (measured); "auto" (1e7 N/m) agrees too but costs 2.5x more.
  sp.pseudo_rigid.internal_stiffness = 1e6;
  sp.pseudo_rigid.internal_auto = false;
  if (rigid) sp.pseudo_rigid.body = scene::PseudoRigid::BodyKind::kRigid;
  RunOptions opts;
  opts.record_trajectory = false;
  const double c0 = thread_cpu();
  const RunResult r = simulate(sp, opts);
  p.cpu_s = thread_cpu() - c0;
  p.wall_s = r.run.cost.wall_time;
  p.status = std::string(reduced::to_string(r.run.status));
  set_ran(p, r);
  p.cost_per_sim_s = p.cpu_s / std::max(r.run.t_end, 1e-9);
  p.strides = static_cast<long>(r.run.strides.size());
  double duty = 0, apex = 0;
  int nd = 0, na = 0;
  for (size_t i = 1; i < r.run.strides.size(); ++i) {
    if (r.run.strides[i].duty_cycle > 0) {
      duty += r.run.strides[i].duty_cycle;
      ++nd;
    }
    if (r.run.strides[i].has_apex) {
      apex += r.run.strides[i].apex_height;
      p.apexes.push_back(r.run.strides[i].apex_height);
      ++na;
    }
  }
  p.mean_duty = nd ? duty / nd : 0.0;
  p.mean_apex = na ? apex / na : 0.0;
  p.note = std::string("one run; force legs; ") +
           (rigid ? "rigid body"
                  : "internal k " + std::to_string(r.monitors.internal_stiffness) + " N/m") +
           "; spectral radius fitted to 4 perturbed runs of 6 s";
  set_fit(p, reduced::estimate_stride_map(sp, simulate_records));
  p.spectral_radius = p.spectral_radius_fit;
  p.spectral_radius_method = "fit";
  p.stable = r.run.status == reduced::RunStatus::kCompleted && p.fit_ok && p.spectral_radius < 1.0;
  return p;
}

}  // namespace

std::vector<FidelityRung> fidelity_rungs() {
  std::vector<FidelityRung> rungs;
  rungs.push_back({"impulse", [](const scene::Scene& s, const BenchConfig& c) {
                     scene::Scene si = s;
                     si.model = scene::ModelKind::kImpulse;
                     return reduced_rung(si, c);
                   }});
  rungs.push_back({"pulse", [](const scene::Scene& s, const BenchConfig& c) {
                     scene::Scene sp = s;
                     sp.model = scene::ModelKind::kPulse;
                     return reduced_rung(sp, c);
                   }});
  rungs.push_back({"rigid", [](const scene::Scene& s, const BenchConfig& c) {
                     return full_model_rung(s, c, true);
                   }});
  rungs.push_back({"pseudo_rigid", [](const scene::Scene& s, const BenchConfig& c) {
                     return full_model_rung(s, c, false);
                   }});
  return rungs;
}

std::vector<FidelityPoint> fidelity_ladder(const BenchConfig& c) {
  scene::Scene base = hopper_scene(c, c.quick ? 4.0 : 10.0);
  const std::vector<double> pulses =
      c.quick ? std::vector<double>{0.1} : std::vector<double>{0.05, 0.1, 0.2, 0.3};
  std::vector<FidelityPoint> out;
  const auto rungs = fidelity_rungs();
  // The impulse model does not depend on the pulse duration: run it once.
  scene::Scene si = base;
  si.model = scene::ModelKind::kImpulse;
  const FidelityPoint impulse = rungs[0].run(si, c);
  const std::vector<double>& impulse_apex = impulse.apexes;
  const reduced::StabilityResult impulse_orbit = reduced::analyze_stability(si);
  out.push_back(impulse);
  for (double T : pulses) {
    scene::Scene s = base;
    s.pulse.duration = T;
    for (size_t r = 1; r < rungs.size(); ++r) {
      FidelityPoint p = rungs[r].run(s, c);
      if (p.available) {
        const std::vector<double>& a = p.apexes;
        const size_t n = std::min(a.size(), impulse_apex.size());
        double sum = 0;
        for (size_t i = 0; i < n; ++i) sum += (a[i] - impulse_apex[i]) * (a[i] - impulse_apex[i]);
        p.apex_rms_vs_impulse = n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
      }
      if (p.available && p.model == "pulse") {
        scene::Scene sp = s;
        sp.model = scene::ModelKind::kPulse;
        const reduced::StabilityResult orbit = reduced::analyze_stability(sp);
        if (orbit.ok && impulse_orbit.ok) {
          p.fixed_point_vs_impulse =
              (orbit.fixed_point - impulse_orbit.fixed_point).cwiseAbs().maxCoeff();
        }
      }
      out.push_back(p);
    }
    // The rigid rung's agreement with the four-mass body at this pulse, apex by apex.
    FidelityPoint* rigid = nullptr;
    const FidelityPoint* four = nullptr;
    for (size_t k = out.size() - (rungs.size() - 1); k < out.size(); ++k) {
      if (out[k].model == "rigid" && out[k].available) rigid = &out[k];
      if (out[k].model == "pseudo_rigid" && out[k].available) four = &out[k];
    }
    if (rigid != nullptr && four != nullptr) {
      const size_t n = std::min(rigid->apexes.size(), four->apexes.size());
      rigid->apex_max_vs_four_mass = 0.0;
      for (size_t i = 0; i < n; ++i) {
        rigid->apex_max_vs_four_mass =
            std::max(rigid->apex_max_vs_four_mass, std::abs(rigid->apexes[i] - four->apexes[i]));
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------- ladder robustness

namespace {

/// The ladder's robustness study for one model: the shipped map_seed_duty study (scene,
/// seed, disturbances, 12 s trials, "stabilized" criterion) at its row 0 (no extra roll: row
/// seeding keys the trials by row, so trial t here is trial t of that row), on a 1-D duty
/// axis, with the first `trials` trials and the full model's settings of the ladder.
optimize::map::MapStudy robustness_study(const BenchConfig& c, const std::string& rung,
                                         const std::vector<double>& duties, long trials) {
  // The rigid rung is the full model with the rigid body.
  const bool rigid = rung == "rigid";
  const std::string model = rigid ? "pseudo_rigid" : rung;
  using nlohmann::json;
  const std::string file = c.studies_dir + "/map_seed_duty.json";
  json doc = io::read_json_file(file);
  doc["name"] = "fidelity_robustness_" + rung;
  doc["models"] = json::array({model});
  doc["axes"] = json::array({json{{"kind", "duty_cycle"}, {"values", duties}}});
  doc["trials"]["count"] = trials;
  doc["stability"] = true;
  // Three bisection probes from a 0.1 bracket (0.1 -> 0.05 -> 0.025 -> 0.0125 wide); the map's
  // default, spacing / 8, rounds to just below 0.0125 and would take a fourth.
  doc["boundary"] = {{"resolution", 0.015}};
  doc["scene_overrides"].push_back(std::string("/pseudo_rigid=") + kFullModelSettings);
  if (rigid) doc["scene_overrides"].push_back("/pseudo_rigid/body=\"rigid\"");
  return optimize::map::parse_map_study(doc, file, c.studies_dir);
}

RungRobustness robustness_rung(const optimize::map::MapStudy& st, const std::string& rung) {
  namespace m = optimize::map;
  RungRobustness r;
  r.model = rung;
  const double c0 = thread_cpu();
  std::vector<m::CellResult> cells;
  for (long i = 0; i < st.cells(); ++i) cells.push_back(m::compute_cell(st, i));
  const std::vector<m::CellSummary> sums = m::summarize(st, cells);
  const m::BoundaryResult b = m::bisect_row(st, m::initial_bracket(st, sums, 0));
  r.cpu_s = thread_cpu() - c0;
  r.boundary_status = b.status;
  r.boundary = b.boundary;
  r.bad = b.bad;
  r.first_good = b.status == "none_good" ? 0.0 : b.first_good;
  r.probes = b.probes;
  const long n = st.trials.count;
  for (size_t i = 0; i < cells.size(); ++i) {
    RobustnessCell cell;
    cell.duty = sums[i].value0;
    cell.trials = n;
    for (const m::TrialOutcome& t : cells[i].trials[0]) {
      cell.verdicts.push_back(t.stabilized);
      cell.stabilized += t.stabilized ? 1 : 0;
      cell.fell += t.status != "completed" ? 1 : 0;
    }
    cell.fraction = static_cast<double>(cell.stabilized) / static_cast<double>(n);
    cell.mean_duty = sums[i].mean_duty;
    cell.spectral_radius = sums[i].spectral_radius;
    r.cells.push_back(std::move(cell));
  }
  return r;
}

}  // namespace

LadderRobustness ladder_robustness(const BenchConfig& c) {
  // Duties across the seed controller's limit (~29 % in map_seed_duty); 8 trials per cell:
  // a 12 s trial of the full model costs ~1.5 s, so its rung (32 trials, 3 bisection probes
  // of up to 8 trials, 4 fitted radii) stays near 2 min; the reduced rungs cost milliseconds.
  const std::vector<double> duties = {0.1, 0.2, 0.3, 0.4};
  const long trials = 8;
  LadderRobustness out;
  out.duties = duties;
  for (const char* model : {"impulse", "pulse", "rigid", "pseudo_rigid"}) {
    const optimize::map::MapStudy st = robustness_study(c, model, duties, trials);
    out.study = st.file + " (row 0: no extra roll)";
    out.trials = st.trials.count;
    out.seed = st.trials.seed;
    out.trial_duration = st.trial_set.duration;
    out.resolution = st.resolution;
    if (c.quick && st.primary_model() == scene::ModelKind::kPseudoRigid) {
      RungRobustness r;
      r.model = model;
      r.available = false;
      r.note = "not run with --quick: the full model costs ~1.5 s per 12 s trial";
      out.rungs.push_back(r);
      continue;
    }
    out.rungs.push_back(robustness_rung(st, model));
  }
  // Disagreements with the pulse rung, trial by trial (the seed's criterion).
  const RungRobustness* pulse = nullptr;
  for (const auto& r : out.rungs)
    if (r.model == "pulse") pulse = &r;
  for (auto& r : out.rungs) {
    if (!r.available || pulse == nullptr) continue;
    for (size_t i = 0; i < r.cells.size(); ++i) {
      RobustnessCell& cell = r.cells[i];
      const auto& ref = pulse->cells[i].verdicts;
      for (size_t t = 0; t < cell.verdicts.size() && t < ref.size(); ++t) {
        cell.only_this += cell.verdicts[t] && !ref[t] ? 1 : 0;
        cell.only_pulse += ref[t] && !cell.verdicts[t] ? 1 : 0;
      }
      r.disagreements_vs_pulse += cell.only_this + cell.only_pulse;
    }
  }
  return out;
}

// ---------------------------------------------------------------- quad hopper drop

nlohmann::json quad_hopper_mechanism(double t_end) {
  // 1.5 kg body with the seed's inertia; four prismatic 100 N/m legs of rest
  // length 0.25 m at the hips (+-0.14, +-0.115, -0.04) m; 10 g feet 0.15 m above the
  // ground. The ground is MuJoCo's default contact made equivalent: Coulomb friction
  // mu = 1 (regularised below 1 mm/s) and a critically damped normal spring
  // (b = 2 sqrt(k m_foot)), so the feet land plastically, as in the MuJoCo peer.
  // Legs and slides are undamped. (With frictionless, elastic contact this hopper is
  // unstable: the feet bounce in every stance, the body rocks from round-off on and
  // tips over after about 2.5 s, so that scene measures a fall, not a drop test.)
  // The energy error is the energy-balance drift: |E + dissipated - E0|.
  using nlohmann::json;
  const double hips[4][2] = {{0.14, 0.115}, {0.14, -0.115}, {-0.14, 0.115}, {-0.14, -0.115}};
  const char* names[4] = {"fl", "fr", "rl", "rr"};
  const double leg = 0.25, drop = 0.15, hip_z = -0.04;
  json body = {{"name", "body"},
               {"mass", 1.5},
               {"inertia", {0.0074, 0.0106, 0.0164}},
               {"com", {0.0, 0.0, drop + leg - hip_z}},
               {"internal_stiffness", 1e5},
               {"ghost_points", json::array()}};
  json masses = json::array(), connections = json::array(), surfaces = json::array();
  json ground_nodes = json::array();
  for (int i = 0; i < 4; ++i) {
    const std::string n = names[i];
    const json hip = {hips[i][0], hips[i][1], hip_z};
    body["ghost_points"].push_back({{"name", "hip_" + n}, {"position", hip}});
    masses.push_back(
        {{"name", "foot_" + n}, {"mass", 0.01}, {"position", {hips[i][0], hips[i][1], drop}}});
    connections.push_back({{"name", "leg_" + n},
                           {"a", "foot_" + n},
                           {"b", "hip_" + n},
                           {"class", "leg"},
                           {"stiffness", 100.0},
                           {"rest_length", leg}});
    surfaces.push_back({{"name", "slide_" + n},
                        {"type", "line"},
                        {"body", "body"},
                        {"point", hip},
                        {"direction", {0, 0, 1}},
                        {"nodes", {"foot_" + n}},
                        {"stiffness", 1e5}});
    ground_nodes.push_back("foot_" + n);
  }
  const double ground_k = 1e5, foot_mass = 0.01;
  surfaces.push_back({{"name", "ground"},
                      {"type", "plane"},
                      {"point", {0, 0, 0}},
                      {"direction", {0, 0, 1}},
                      {"nodes", ground_nodes},
                      {"stiffness", ground_k},
                      {"damping", 2.0 * std::sqrt(ground_k * foot_mass)},
                      {"friction", 1.0}});
  return {{"kind", "mechanism"},
          {"name", "quad_hopper_drop"},
          {"gravity", {0, 0, -9.81}},
          {"bodies", {body}},
          {"masses", masses},
          {"connections", connections},
          {"surfaces", surfaces},
          {"simulation",
           {{"t_end", t_end},
            {"output_interval", 1e-3},
            {"method", "rodas4"},
            {"rtol", 1e-6},
            {"atol", 1e-6}}}};
}

namespace {

/// One timed run of the quad hopper drop.
struct QuadDropSetting {
  Method method;
  double tol;  ///< rtol = atol (RODAS4) or the fixed step h [s] (Verlet)
  pr::ErrorNorm norm;
  double energy_tol = 0.0;  ///< Verlet: simulation.energy_tol (0: every step at h)
  bool rigid = false;       ///< the body as one rigid body
};

std::vector<QuadDropSetting> quad_drop_settings(bool quick) {
  std::vector<QuadDropSetting> settings;
  for (double tol : quick ? std::vector<double>{1e-5} : std::vector<double>{1e-4, 1e-5, 1e-6}) {
    for (auto norm : {pr::ErrorNorm::kState, pr::ErrorNorm::kBody}) {
      settings.push_back({Method::kRodas4, tol, norm});
    }
  }
  // Verlet with the dissipation split: the regularised friction (mu N / v_s per unit foot
  // mass, ~1e6 1/s in stance) and the contact damper are implicit, so the step is limited by
  // the 1e5 N/m springs on the 10 g feet (omega ~ 3200 rad/s: h < 6e-4 s).
  for (double h : quick ? std::vector<double>{5e-4} : std::vector<double>{5e-4, 2.5e-4, 1e-4}) {
    settings.push_back({Method::kVerlet, h, pr::ErrorNorm::kState});
  }
  // Verlet with an energy budget: 5e-4 s steps, the impacts sub-stepped so that Verlet's
  // bounded term stays within 1e-4 of the energy scale (8.9 J; 1e-4 of it is 3.9e-4 of the
  // drop energy) at every step.
  settings.push_back({Method::kVerlet, 5e-4, pr::ErrorNorm::kState, 1e-4});
  // The rigid body: RODAS4 (its Jacobian by differences) and Verlet as above; the feet on
  // their 1e5 N/m slides still bound Verlet's step.
  settings.push_back({Method::kRodas4, 1e-5, pr::ErrorNorm::kState, 0.0, true});
  settings.push_back({Method::kVerlet, 5e-4, pr::ErrorNorm::kState, 0.0, true});
  settings.push_back({Method::kVerlet, 5e-4, pr::ErrorNorm::kState, 1e-4, true});
  return settings;
}

std::vector<double> quad_drop_apex_heights(const pr::Mechanism& m, const pr::RunSummary& r,
                                           std::vector<size_t>* index) {
  // Body CoM height on the output grid; apexes are local maxima of z while the body moves
  // up then down (refined by a parabola through three samples); only the body's flight
  // apexes count (foot vibration makes tiny wiggles).
  const pr::MechanismSystem sys(m);
  std::vector<double> z, out;
  for (const auto& y : r.y) z.push_back(sys.frames(y)[0].com.z());
  for (size_t i = 1; i + 1 < z.size(); ++i) {
    if (z[i] > z[i - 1] && z[i] >= z[i + 1] && z[i] > z.front() - 0.075) {
      const double den = z[i - 1] - 2 * z[i] + z[i + 1];
      const double off = den != 0 ? 0.5 * (z[i - 1] - z[i + 1]) / den : 0.0;
      out.push_back(z[i] - 0.25 * (z[i - 1] - z[i + 1]) * off);
      if (index != nullptr) index->push_back(i);
    }
  }
  return out;
}

/// One setting run and measured against the reference apex heights `ref`.
nlohmann::json quad_drop_run(const QuadDropSetting& setting, pr::Mechanism m, double t_end,
                             const std::vector<double>& ref, int repeat) {
  const double tol = setting.tol;
  const pr::ErrorNorm norm = setting.norm;
  m.simulation.solver.method = setting.method;
  m.simulation.solver.rtol = m.simulation.solver.atol = tol;
  if (setting.method == Method::kVerlet) m.simulation.solver.h_fixed = tol;
  m.simulation.energy_tol = setting.energy_tol;
  m.simulation.error_norm = norm;
  // Timed `repeat` times (median) while a run is cheap; a run over 0.5 s (the stiff methods
  // at tight tolerances) once, so the bench stays within its budget.
  std::vector<double> cpus, walls;
  pr::RunSummary r;
  for (int k = 0; k < std::max(1, repeat); ++k) {
    const double c0 = thread_cpu();
    r = pr::simulate(m);
    cpus.push_back(thread_cpu() - c0);
    walls.push_back(r.wall_time);
    if (cpus.back() > 0.5) break;
  }
  std::vector<size_t> at_apex;
  const std::vector<double> a = quad_drop_apex_heights(m, r, &at_apex);
  const double z0 = pr::MechanismSystem(m).frames(r.y.front())[0].com.z(), drop = 0.15;
  // Energy balance at the flight apexes, where the forces on the feet are small: the
  // hop-to-hop drift (case 6's criterion), without the transient of a fixed-step method
  // inside an impact (Verlet: E - E_modified = h^2 |F|^2 / 8m, up to ~1e-1 J while a
  // foot is stopped at h = 5e-4 s).
  const double balance0 = r.energies.front().total();
  double apex_balance = 0, apex_vs_ref = 0;
  std::vector<double> ae;
  for (size_t i : at_apex) {
    ae.push_back(r.energies[i].total());
    apex_balance = std::max(apex_balance, std::abs(r.energies[i].total() + r.dissipated[i] -
                                                   r.actuator_work[i] - balance0));
  }
  for (size_t i = 0; i < a.size() && i < ref.size(); ++i) {
    apex_vs_ref = std::max(apex_vs_ref, std::abs(a[i] - ref[i]) / drop);
  }
  double apex_err = 0;
  for (double h : a) apex_err = std::max(apex_err, std::abs(h - z0) / drop);
  const double e0 = r.energies.front().total();
  // Energy reference: the drop energy m g h (mechanical energy above the state
  // standing on the ground is not well defined in both tools; this is).
  const double drop_energy = m.total_mass() * 9.81 * drop;
  return {{"method", std::string(ode::to_string(setting.method))},
          {"body", setting.rigid ? "rigid" : "four_masses"},
          {"tol", setting.method == Method::kVerlet ? 0.0 : tol},
          {"h", setting.method == Method::kVerlet ? tol : 0.0},
          {"energy_tol", setting.energy_tol},
          {"norm", norm == pr::ErrorNorm::kBody ? "body" : "state"},
          {"t_end", t_end},
          {"status", std::string(pr::to_string(r.status))},
          {"wall_s", median(walls)},
          {"cpu_s", median(cpus)},
          {"cost_per_sim_s", median(cpus) / t_end},
          {"steps", r.counters.steps_accepted},
          {"rejected", r.counters.steps_rejected},
          {"rhs", r.counters.rhs_evaluations},
          {"jacobians", r.counters.jacobian_evaluations},
          {"lu", r.counters.lu_factorizations},
          {"energy_drift_rel", r.energy_drift / r.energy_scale},
          {"energy_error_rel", r.energy_drift / drop_energy},
          {"energy_error_apex_rel", apex_balance / drop_energy},
          {"apex_height_vs_reference_rel", ref.empty() ? -1.0 : apex_vs_ref},
          {"bounces", a.size()},
          {"apex_heights_m", a},
          {"apex_height_error_rel", apex_err},
          {"first_bounce_energy_loss_rel", ae.empty() ? 0.0 : (e0 - ae.front()) / drop_energy},
          {"max_strain", r.max_strain},
          {"max_penetration_m", r.max_penetration}};
}

}  // namespace

nlohmann::json quad_hopper_drop(const BenchConfig& c) {
  const double t_end = c.quick ? 2.0 : 10.0;
  const nlohmann::json doc = quad_hopper_mechanism(t_end);
  const pr::Mechanism base = io::parse_mechanism(doc, "<quad_hopper_drop>").mechanism;
  // The same hopper with its body as one rigid body (the mechanism's "rigid": true).
  nlohmann::json doc_rigid = doc;
  doc_rigid["bodies"][0]["rigid"] = true;
  const pr::Mechanism base_rigid =
      io::parse_mechanism(doc_rigid, "<quad_hopper_drop_rigid>").mechanism;
  // 10 s of the drop costs seconds per run on the stiff methods: those run once, the cheap
  // ones c.repeat times (quad_drop_run), so the bench stays within its budget.
  const std::vector<QuadDropSetting> settings = quad_drop_settings(c.quick);
  // The reference for the apex heights: RODAS4 at tol 1e-8 (not timed).
  // (The rigid rows against the rigid body's own reference: at 1e5 N/m the four-mass body
  // flexes by ~0.3 %, and the two differ by ~9 % of the drop in apex height.)
  std::vector<double> z_ref, z_ref_rigid;
  for (const bool rigid : {false, true}) {
    pr::Mechanism m = rigid ? base_rigid : base;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-8;
    if (!rigid) m.simulation.error_norm = pr::ErrorNorm::kBody;
    const pr::RunSummary r = pr::simulate(m);
    if (r.status == pr::RunStatus::kCompleted) {
      (rigid ? z_ref_rigid : z_ref) = quad_drop_apex_heights(m, r, nullptr);
    }
  }
  nlohmann::json out = nlohmann::json::array();
  for (const QuadDropSetting& setting : settings) {
    out.push_back(quad_drop_run(setting, setting.rigid ? base_rigid : base, t_end,
                                setting.rigid ? z_ref_rigid : z_ref, c.repeat));
  }
  return out;
}

}  // namespace pronk::app::bench
