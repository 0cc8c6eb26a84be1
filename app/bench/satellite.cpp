// `pronk bench`'s satellite: work-precision of every solver on the pseudo-rigid satellite
// (k = 1e6 N/m, 20 s) and the internal stiffness sweep (1e4 .. 1e8 N/m), both against the
// analytic precession and a tight reference run.
#include <cmath>
#include <string>
#include <vector>

#include "app/bench/suite.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
// The satellite scene is shared by the tests, bench_pseudorigid and this bench.
#include "tests/pseudorigid/scenes.hpp"

namespace pronk::app::bench {

namespace pr = pronk::pseudorigid;
using ode::Method;

namespace {

constexpr double kSatelliteEnd = 20.0;  // [s], issue 3

pr::Mechanism satellite(double k, Method method, double tol, double h, pr::ErrorNorm norm) {
  pr::Mechanism m = pr::test_scenes::satellite(k, kSatelliteEnd);
  m.simulation.solver.method = method;
  m.simulation.solver.rtol = m.simulation.solver.atol = tol > 0 ? tol : 1e-6;
  if (h > 0) m.simulation.solver.h_fixed = h;
  m.simulation.error_norm = norm;
  return m;
}

/// A timed satellite run. A diverged explicit run is measured once: its cost is not the point.
using SatelliteRun = Timed<pr::RunSummary>;

SatelliteRun run_satellite(const pr::Mechanism& m, int repeat) {
  return timed(
      repeat, [&] { return pr::simulate(m); },
      [](const pr::RunSummary& r, double) { return r.status != pr::RunStatus::kCompleted; });
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
  p.status = std::string(pr::to_string(run.result.status));
  p.cost = cost_of(run, run.result.counters);
  if (run.result.status != pr::RunStatus::kCompleted) return p;
  const auto w = omega_series(m, run.result);
  const double w0 = pr::test_scenes::satellite_omega(0.0).norm();
  p.errors["omega_final"] =
      (w.back() - pr::test_scenes::satellite_omega(run.result.t.back())).norm() / w0;
  if (ref != nullptr && ref->y.size() == run.result.y.size()) {
    p.errors["omega_final_ref"] = (w.back() - ref_omega->back()).norm() / w0;
    double s = 0.0;
    for (size_t i = 0; i < w.size(); ++i) s += ((w[i] - (*ref_omega)[i]) / w0).squaredNorm();
    p.errors["omega_l2"] = std::sqrt(s / static_cast<double>(w.size()));
    const Eigen::VectorXd d = run.result.y.back() - ref->y.back();
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

}  // namespace

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
  // must end with a divergence status, which is what they show.
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

}  // namespace pronk::app::bench
