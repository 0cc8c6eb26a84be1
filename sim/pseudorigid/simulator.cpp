#include "sim/pseudorigid/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Eigenvalues>

#include "sim/ode/verlet.hpp"
#include "sim/pseudorigid/solver_norm.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/run/hybrid_run.hpp"

namespace pronk::pseudorigid {

std::string_view to_string(RunStatus s) {
  return s == RunStatus::kCompleted ? "completed" : "diverged";
}

namespace {

/// Times at which a time-windowed force switches, inside (0, t_end), plus t_end.
std::vector<double> breakpoints(const Mechanism& m) {
  const double te = m.simulation.t_end;
  std::vector<double> b{te};
  auto add = [&](double t) {
    if (t > 0.0 && t < te && std::isfinite(t)) b.push_back(t);
  };
  for (const auto& f : m.body_forces) {
    add(f.t_start);
    add(f.t_end);
  }
  for (const auto& a : m.impulse_actuators) {
    add(a.t_start);
    add(a.t_start + a.duration());
  }
  std::sort(b.begin(), b.end());
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

/// Smallest/largest principal moment below which a body counts as a slender rod.
constexpr double kSlenderRatio = 1e-2;
/// Energy-balance drift, relative to the energy scale, above which a completed run warns.
constexpr double kEnergyDriftWarning = 1e-2;
/// Estimated relative spin-rate error of a slender body above which the run warns.
constexpr double kSpinErrorLimit = 1e-3;

/// Gauss-Legendre 3-point nodes and weights on [0, 1].
const double kGaussNodes[3] = {0.5 - std::sqrt(15.0) / 10.0, 0.5, 0.5 + std::sqrt(15.0) / 10.0};
const double kGaussWeights[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

/// One mechanism run on the hybrid loop: segments between the breakpoints of the
/// time-windowed forces, no state events. Along the accepted steps (the loop's step observer)
/// it integrates the energy flows, samples the output grid, keeps the monitors and checks
/// divergence (non-finite state, energy blow-up, crawl, step budget), stopping the loop.
class MechanismRun final : public run::HybridModel, public ode::StepObserver {
 public:
  MechanismRun(const Mechanism& m, MechanismSystem& sys, RunSummary& out)
      : m_(m),
        opt_(m.simulation),
        sys_(sys),
        out_(out),
        bps_(breakpoints(m)),
        yq_(sys.dimension()) {
    // The loop's own budget checks stay off: this run checks the whole run's step attempts
    // against the simulated time after every step (on_step).
    guards_off_ = opt_.solver;
    guards_off_.max_steps = std::numeric_limits<long>::max();
    guards_off_.max_steps_per_second = 0.0;
    sys_.set_segment_time(0.5 * bps_.front());
    out_.max_surface_force.assign(m.surfaces.size(), 0.0);
  }

  /// Records the initial state and sets the energy scale; returns the solver options (verlet's
  /// energy budget in joules).
  ode::SolverOptions begin(const ode::Vec& y);
  /// Drops non-finite samples and sets the drift monitor, t_reached and the counters.
  void finish(const ode::Stepper& stepper);
  /// |E + dissipated - actuator work - balance at t = 0| at sample i [J].
  double sample_drift(size_t i) const {
    return std::abs(out_.energies[i].total() + out_.dissipated[i] - out_.actuator_work[i] -
                    balance0_);
  }
  bool diverged() const { return diverged_; }

  const ode::OdeSystem& system() const override { return sys_; }
  const ode::SolverOptions& integration_options() const override { return guards_off_; }
  void start(const ode::Stepper& stepper, const ode::Vec&) override {
    booked_a_ = ode::booked_dissipation(stepper);
  }
  double segment_end(double) const override { return bps_[bi_]; }
  std::span<const ode::EventFunction* const> events() const override { return {}; }
  ode::StepObserver* observer() override { return this; }
  void on_failure(const run::Segment& seg, const ode::Vec&, const ode::Stepper& st) override {
    if (seg.integrated.reason == ode::StopReason::kStopped) return;  // on_step said why
    char buf[400];
    std::snprintf(buf, sizeof buf, "%s at t = %.9g s (step %.3g s)",
                  seg.integrated.reason == ode::StopReason::kNonFinite ? "non-finite state"
                                                                       : "step-size collapse",
                  st.t(), st.h());
    diverge(buf);
  }
  run::Next on_segment_end(const run::Segment& seg, ode::Vec&, const ode::Stepper&) override {
    if (++bi_ == bps_.size()) return run::Next::kStop;
    sys_.set_segment_time(0.5 * (seg.t + bps_[bi_]));
    return run::Next::kContinue;
  }

  void on_step(const ode::Stepper& stepper, double t_stop) override;
  bool stop_requested() const override { return diverged_; }

 private:
  void diverge(const std::string& why) {
    out_.status = RunStatus::kDiverged;
    out_.reason = why;
    diverged_ = true;
  }
  void record(double t, const ode::Vec& ys, double dissipated_t, double work_t,
              const Energies* known = nullptr) {
    out_.t.push_back(t);
    out_.y.push_back(ys);
    out_.energies.push_back(known != nullptr ? *known : sys_.energies(ys));
    out_.dissipated.push_back(dissipated_t);
    out_.actuator_work.push_back(work_t);
  }
  /// Monitors of a state; returns its energies (one pass over the surfaces for all three).
  Energies monitor(const ode::Vec& ys) {
    Energies e;
    StateMonitors mon;
    sys_.observe(ys, &e, &mon, &out_.max_surface_force);
    out_.max_strain = std::max(out_.max_strain, mon.max_strain);
    out_.max_penetration = std::max(out_.max_penetration, mon.max_penetration);
    return e;
  }
  /// Adds the dissipation and actuator work over [ta, te] (te <= the step's end) to *d, *w:
  /// by Gauss-Legendre on the step's dense output, or, for a stepper that books the
  /// dissipation itself (MechanicalSystem::dissipate; linear in time inside a step), from its books
  /// (the actuator work is then the only integral).
  void flows(const ode::Stepper& st, double te, double booked_b, double dissipated_a, double* d,
             double* w) {
    const double ta = st.t_prev(), tb = st.t();
    const bool booked = ode::books_dissipation(st);
    if (booked) *d = dissipated_a + (booked_b - booked_a_) * (te - ta) / (tb - ta);
    if (!sys_.has_power_flows() || (booked && !sys_.has_actuator_work())) return;
    for (int q = 0; q < 3; ++q) {
      st.dense(ta + kGaussNodes[q] * (te - ta), yq_);
      const PowerFlows p = sys_.power(yq_);
      if (!booked) *d += kGaussWeights[q] * (te - ta) * p.dissipated;
      *w += kGaussWeights[q] * (te - ta) * p.actuator;
    }
  }
  void check_step(double tb, const Energies& eb, const ode::SolverCounters& c);

  const Mechanism& m_;
  const SimulationOptions& opt_;
  MechanismSystem& sys_;
  RunSummary& out_;
  const std::vector<double> bps_;
  size_t bi_ = 0;  ///< the breakpoint the current segment ends at
  ode::SolverOptions guards_off_;
  ode::Vec yq_;
  double dissipated_ = 0.0, work_ = 0.0;
  double booked_a_ = 0.0;  ///< the stepper's booked dissipation at the current step's start [J]
  double next_out_ = 0.0;
  double balance0_ = 0.0, blowup_ = 0.0;
  bool diverged_ = false;
};

ode::SolverOptions MechanismRun::begin(const ode::Vec& y) {
  // The samples' storage at once (a run that stops early keeps the capacity).
  const double samples = std::floor(opt_.t_end / opt_.output_interval) + 2.0;
  if (samples > 0.0 && samples < 1e7) {
    const auto n = static_cast<size_t>(samples);
    out_.t.reserve(n);
    out_.y.reserve(n);
    out_.energies.reserve(n);
    out_.dissipated.reserve(n);
    out_.actuator_work.reserve(n);
  }
  record(0.0, y, 0.0, 0.0);
  monitor(y);
  const Energies e0 = out_.energies.front();
  balance0_ = e0.total();
  // Energy scale: motion and stored energy, plus lifting the whole mass over the scene size.
  Eigen::Vector3d lo = m_.masses[0].position, hi = lo;
  for (const Mass& ms : m_.masses) {
    lo = lo.cwiseMin(ms.position);
    hi = hi.cwiseMax(ms.position);
  }
  for (const Anchor& a : m_.anchors) {
    lo = lo.cwiseMin(a.position);
    hi = hi.cwiseMax(a.position);
  }
  for (const Surface& s : m_.surfaces) {
    if (s.body >= 0) continue;
    lo = lo.cwiseMin(s.point);
    hi = hi.cwiseMax(s.point);
  }
  out_.energy_scale = e0.kinetic + e0.internal + e0.leg + e0.other + e0.contact +
                      m_.total_mass() * m_.gravity.norm() * (hi - lo).norm() + 1e-9;
  blowup_ = opt_.energy_blowup_factor * out_.energy_scale;
  next_out_ = opt_.output_interval;
  // Method verlet with an energy tolerance: the bound on its bounded term in joules.
  ode::SolverOptions solver = opt_.solver;
  if (solver.method == ode::Method::kVerlet && opt_.energy_tol > 0.0) {
    solver.verlet_energy_budget = opt_.energy_tol * out_.energy_scale;
  }
  return solver;
}

void MechanismRun::on_step(const ode::Stepper& stepper, double) {
  const double tb = stepper.t();
  const ode::Vec& yb = stepper.y();
  const double dissipated_a = dissipated_, work_a = work_;
  if (!yb.allFinite()) {
    char buf[100];
    std::snprintf(buf, sizeof buf, "non-finite state at t = %.9g s", tb);
    diverge(buf);
    return;
  }
  const double booked_b = ode::booked_dissipation(stepper);
  flows(stepper, tb, booked_b, dissipated_a, &dissipated_, &work_);
  const Energies eb = monitor(yb);
  while (next_out_ <= tb * (1.0 + 1e-12) && next_out_ <= opt_.t_end * (1.0 + 1e-12)) {
    const double ts = std::min(next_out_, tb);
    // A sample inside the step pairs its energies with the flows up to the sample time,
    // not up to the step end (that mismatch showed as a balance drift of the order of
    // one step's dissipation: 2.5 % of the energy in a damped two-mass oscillator).
    if (ts < tb) {
      double ds = dissipated_a, ws = work_a;
      flows(stepper, ts, booked_b, dissipated_a, &ds, &ws);
      stepper.dense(ts, yq_);
      record(next_out_, yq_, ds, ws);
    } else {
      record(next_out_, yb, dissipated_, work_, &eb);  // the step's end: state and energies
    }
    next_out_ = opt_.output_interval * static_cast<double>(out_.t.size());
  }
  booked_a_ = booked_b;
  check_step(tb, eb, stepper.counters());
}

/// Divergence after an accepted step ending at tb: energy blow-up, crawl, step budget.
void MechanismRun::check_step(double tb, const Energies& eb, const ode::SolverCounters& c) {
  const double balance = eb.total() + dissipated_ - work_;
  const double drift = std::abs(balance - balance0_);
  if (!std::isfinite(balance) || drift > blowup_) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "energy blow-up at t = %.9g s: energy balance drifted by %.3g J (scale %.3g "
                  "J); the solver is beyond its stability limit or the step is too large",
                  tb, drift, out_.energy_scale);
    diverge(buf);
    return;
  }
  const long attempts = c.steps_accepted + c.steps_rejected;  // the whole run's
  if (opt_.solver.crawling(attempts, tb)) {
    diverge(opt_.solver.crawl_reason(attempts, tb, tb));
    return;
  }
  if (attempts >= opt_.solver.max_steps) diverge(opt_.solver.step_limit_reason(attempts, tb));
}

void MechanismRun::finish(const ode::Stepper& stepper) {
  // Samples only hold finite values: a diverged run keeps the samples before divergence.
  while (!out_.y.empty() &&
         !(out_.y.back().allFinite() && std::isfinite(out_.energies.back().total()))) {
    out_.t.pop_back();
    out_.y.pop_back();
    out_.energies.pop_back();
    out_.dissipated.pop_back();
    out_.actuator_work.pop_back();
  }
  for (size_t i = 0; i < out_.t.size(); ++i) {
    out_.energy_drift = std::max(out_.energy_drift, sample_drift(i));
  }
  out_.t_reached = diverged_ ? (out_.t.empty() ? 0.0 : out_.t.back()) : stepper.t();
  out_.counters = stepper.counters();
  out_.zero_length_triggers = sys_.zero_length_triggers();
  if (!std::isfinite(out_.max_strain)) out_.max_strain = 1e300;
  if (!std::isfinite(out_.max_penetration)) out_.max_penetration = 1e300;
  for (double& f : out_.max_surface_force) {
    if (!std::isfinite(f)) f = 1e300;
  }
  if (!std::isfinite(out_.jacobian_check_error)) out_.jacobian_check_error = 1e300;
}

/// near_degenerate_inertia: a slender body whose spin rate the internal strain perturbs.
void warn_slender_bodies(const Mechanism& m, RunSummary& out) {
  char buf[400];
  for (const Body& b : m.bodies) {
    const Eigen::Vector3d moments =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(b.inertia, Eigen::EigenvaluesOnly)
            .eigenvalues();
    const double ratio = moments.minCoeff() / moments.maxCoeff();
    // Measured (slender rod, k = 1e6, any rtol): the spin-rate error is ~0.2 x max strain x
    // Imax/Imin, independent of the solver tolerance: the axial spin lives in the tiny
    // lateral offsets of the four masses, which the elastic deformation perturbs.
    const double spin_error = out.max_strain / ratio;
    if (ratio < kSlenderRatio && spin_error > kSpinErrorLimit &&
        !out.warnings.count("near_degenerate_inertia")) {
      std::snprintf(buf, sizeof buf,
                    "body %s is nearly a slender rod (smallest principal moment %.3g of the "
                    "largest): its spin about that axis carries almost no angular momentum and "
                    "the internal strain perturbs the spin rate by up to about max strain x "
                    "Imax/Imin = %.3g (relative); angular momentum and energy stay accurate, "
                    "stiffer internal springs resolve the spin",
                    b.name.c_str(), ratio, spin_error);
      out.warnings["near_degenerate_inertia"] = buf;
    }
  }
}

/// energy_balance_drift: a completed run whose balance drifted by more than 1e-2 of the scale.
/// end_drift: the drift at the last sample [J]; verlet: the stepper books the dissipation.
void warn_energy_drift(RunSummary& out, double end_drift, bool verlet) {
  if (!(out.status == RunStatus::kCompleted &&
        out.energy_drift > kEnergyDriftWarning * out.energy_scale)) {
    return;
  }
  // Below the blow-up factor, but not solver accuracy either: e.g. explicit Euler slowly
  // pumping the internal vibration (1e-2 ... 10 of the scale before it is a blow-up).
  char text[800];
  if (verlet && end_drift <= kEnergyDriftWarning * out.energy_scale) {
    // Verlet's energy departs from its exactly balanced modified energy by
    // h^2 |F|^2 / 8m where large forces act on light masses, and returns from it (the
    // quad hopper drop at h = 5e-4 s: 4.4e-2 of the drop energy inside impacts, 2.4e-5 at
    // the flight apexes).
    std::snprintf(text, sizeof text,
                  "the energy balance departed by %.3g J, %.3g of the energy scale %.3g J, at "
                  "its worst sample but by %.3g J at the end: method verlet's energy carries "
                  "the bounded term h^2 |F|^2 / 8m where large forces act on light masses "
                  "(impacts) and returns from it; read the balance between such events, or set "
                  "simulation.energy_tol (sub-steps the impacts) or halve h_fixed",
                  out.energy_drift, out.energy_drift / out.energy_scale, out.energy_scale,
                  end_drift);
  } else {
    std::snprintf(text, sizeof text,
                  "the energy balance drifted by %.3g J, %.3g of the energy scale %.3g J: the "
                  "step is too large or the tolerance too loose (an explicit solver near its "
                  "stability limit, or the min_norm ghost transfer); do not read this run as "
                  "physics",
                  out.energy_drift, out.energy_drift / out.energy_scale, out.energy_scale);
  }
  out.warnings["energy_balance_drift"] = text;
}

/// The accuracy monitors against their budgets, and the zero-length rule.
void warn_budgets(const SimulationOptions& opt, RunSummary& out) {
  char buf[400];
  if (out.max_strain > opt.strain_budget) {
    std::snprintf(buf, sizeof buf,
                  "max internal strain %.3g exceeds the strain budget %.3g: the bodies flexed, "
                  "so the pseudo-rigid approximation did not hold (stiffen the internal springs "
                  "or use \"internal_stiffness\": \"auto\")",
                  out.max_strain, opt.strain_budget);
    out.warnings["strain_above_budget"] = buf;
  }
  if (out.max_penetration > opt.penetration_budget) {
    std::snprintf(buf, sizeof buf,
                  "max penetration / constraint violation %.3g m exceeds the penetration budget "
                  "%.3g m (stiffen the surfaces or use \"contact_stiffness\": \"auto\")",
                  out.max_penetration, opt.penetration_budget);
    out.warnings["penetration_above_budget"] = buf;
  }
  if (out.zero_length_triggers > 0) {
    std::snprintf(buf, sizeof buf,
                  "the zero-length rule fired in %ld RHS evaluations: a connection shorter than "
                  "%.3g m has no direction, its spring (rest length > 0) and damper terms were "
                  "dropped there",
                  out.zero_length_triggers, opt.zero_length_epsilon);
    out.warnings["zero_length_rule"] = buf;
  }
}

}  // namespace

RunSummary simulate(const Mechanism& m) {
  const auto t0 = std::chrono::steady_clock::now();
  RunSummary out;
  MechanismSystem sys(m);
  const ode::Vec y = m.initial_state();
  if (m.simulation.check_jacobian) out.jacobian_check_error = jacobian_check(sys, 0.0, y);
  MechanismRun hybrid(m, sys, out);
  auto stepper = ode::make_stepper(hybrid.begin(y), sys.dimension(),
                                   solver_norm(m, sys, /*mass_scaled=*/true));
  run::run_hybrid(hybrid, *stepper, 0.0, y);
  hybrid.finish(*stepper);
  // Warnings: near-degenerate bodies, the accuracy monitors against their budgets, and the
  // zero-length rule.
  warn_slender_bodies(m, out);
  warn_energy_drift(out, out.t.empty() ? 0.0 : hybrid.sample_drift(out.t.size() - 1),
                    ode::books_dissipation(*stepper));
  warn_budgets(m.simulation, out);
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pronk::pseudorigid
