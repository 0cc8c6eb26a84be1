// `pronk bench`'s fidelity ladder: the legged hopper in the impulse and pulse models, and in
// the full model with a rigid and a four-mass body, at a few pulse durations: cost, apexes,
// duty and the stride map's spectral radius (evaluated, or fitted to perturbed runs).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/bench/suite.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/reduced/stride_fit.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/simulate.hpp"

namespace pronk::app::bench {

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

/// What a rung's run was: the model simulate() ran and its solver's counters.
void set_ran(FidelityPoint& p, const RunResult& r) {
  p.ran_model = std::string(scene::to_string(r.model));
  p.rhs_evaluations = r.run.cost.solver.rhs_evaluations;
  p.jacobians = r.run.cost.solver.jacobian_evaluations;
}

/// The strides' means over strides 2..: duty cycle, apex height (and each apex into p.apexes).
void set_strides(FidelityPoint& p, const reduced::RunResult& r) {
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
}

FidelityPoint reduced_rung(const scene::Scene& s, const BenchConfig& c) {
  FidelityPoint p;
  p.model = std::string(scene::to_string(s.model));
  p.pulse_duration = s.model == scene::ModelKind::kPulse ? s.pulse.duration : 0.0;
  p.t_end = s.simulation.duration;
  RunOptions opts;
  opts.record_trajectory = false;
  const Timed<RunResult> run = timed(c.repeat, [&] { return simulate(s, opts); });
  const reduced::RunResult& r = run.result.run;
  set_ran(p, run.result);
  p.status = std::string(reduced::to_string(r.status));
  p.wall_s = run.wall_s;
  p.cpu_s = run.cpu_s;
  p.cost_per_sim_s = p.cpu_s / std::max(r.t_end, 1e-9);
  set_strides(p, r);
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
  sp.pseudo_rigid.body =
      rigid ? scene::PseudoRigid::BodyKind::kRigid : scene::PseudoRigid::BodyKind::kFourMasses;
  RunOptions opts;
  opts.record_trajectory = false;
  const Timed<RunResult> run = timed(1, [&] { return simulate(sp, opts); });
  const RunResult& r = run.result;
  p.cpu_s = run.cpu_s;
  p.wall_s = run.wall_s;
  p.status = std::string(reduced::to_string(r.run.status));
  set_ran(p, r);
  p.cost_per_sim_s = p.cpu_s / std::max(r.run.t_end, 1e-9);
  set_strides(p, r.run);
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

}  // namespace pronk::app::bench
