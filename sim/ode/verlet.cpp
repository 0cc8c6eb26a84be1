// Velocity Verlet (Stormer-Verlet, kick-drift-kick) on a MechanicalSystem y = (q, p),
// dq/dt = G(p), dp/dt = F(t, q, p): fixed step, order 2, symplectic and time-reversible when
// F does not depend on p; one full RHS per step (F at the new positions is also the first
// kick of the next step) plus two cheap position_rate() calls.
// - With the system's dissipation split, each half kick is followed by the dissipative
//   forces over h/2 at fixed positions, solved implicitly by the system (together a
//   backward Euler half step of the momenta), and the dissipated energy is booked so that
//   E - T + D is exactly constant for quadratic potentials (T = sum h^2 |F|^2 / 8m).
// - Without it, velocity-dependent forces in the closing kick are evaluated at the
//   predicted momentum p* = p_half + h/2 F_n (explicit, order 2, not symplectic).
// - Booking with the held force: the difference between T and T_net = sum h^2 |F + a F_d|^2
//   / 8m (a in [0, 1] per momentum block, the share of the dissipative force F_d that
//   cancels F) moves from D to T at every point, so E - T_net + D stays exactly constant.
// - Energy budget (SolverOptions::verlet_energy_budget): h_fixed is the grid step, taken as
//   2^j sub-steps; a sub-step whose T_net exceeds the budget is retried finer, and grid
//   points coarsen by small switches or ones that undo the switching offset.
// Stable for h < 2 / omega_max of the springs. Why and how much: docs/pseudorigid.md,
// "Solver: velocity Verlet".
#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "sim/ode/mechanical_system.hpp"
#include "sim/ode/steppers.hpp"
#include "sim/ode/verlet.hpp"

namespace pronk::ode::detail {
namespace {

class VerletStepper final : public Stepper, public VerletInfo {
 public:
  VerletStepper(const SolverOptions& options, int n)
      : h_fixed_(options.h_fixed),
        budget_(options.verlet_energy_budget),
        h_min_(options.h_min),
        y_(Vec::Zero(n)),
        y_prev_(Vec::Zero(n)),
        y_new_(Vec::Zero(n)),
        f_(Vec::Zero(n)),
        f_prev_(Vec::Zero(n)),
        f_new_(Vec::Zero(n)),
        fd_(Vec::Zero(n)),
        fd_new_(Vec::Zero(n)),
        fd_prev_(Vec::Zero(n)),
        slope_a_(Vec::Zero(n)),
        slope_b_(Vec::Zero(n)),
        p_half_(Vec::Zero(n)),
        y_ref_(Vec::Zero(n)),
        y_start_(Vec::Zero(n)),
        f_start_(Vec::Zero(n)),
        work_(Vec::Zero(n)),
        mask_(Vec::Zero(n)),
        q_mask_(Vec::Zero(n)) {}

  void reset(const OdeSystem& system, double t, const Vec& y) override {
    assert(y.size() == y_.size());
    const MechanicalSystem& sys = take(system);
    sys.momentum_mask(mask_);
    split_ = sys.has_dissipation_split();
    drift_ = sys.has_drift();
    relax_ = sys.has_relaxation();
    block_ = std::max(1, sys.momentum_block());
    const bool has_metric = sys.kinetic_energy(y) >= 0.0;
    if (budget_ > 0.0 && !has_metric) {
      throw std::invalid_argument(
          "verlet_energy_budget needs the system's kinetic-energy metric; this system has none");
    }
    // Without the split T_net is T and the booking needs no correction: the metric is then
    // evaluated only for a budget.
    metric_ = has_metric && (split_ || budget_ > 0.0);
    q_mask_ = Vec::Ones(mask_.size()) - mask_;
    t_ = t;
    t_prev_ = t;
    t_base_ = t;
    start_.t_end = t;  // no step to retake
    steps_since_base_ = 0;
    remaining_ = 0;  // a new grid step starts here; the planned sub-steps are kept
    y_ = y;
    y_prev_ = y;
    opened_relaxed_ = false;
    forces(sys, t_, y_, f_);
    kick_ = y;
    kick_prev_ = y;
    f_prev_ = f_;
    // The dissipative force at the restart point: the mean one of the next opening half step
    // (it has no closing one), so a foot held at the start starts with T_net near zero. The
    // change of T_net, like a step-size switch, enters the switching offset.
    if (split_) {
      const double h = h_fixed_ / substeps_;
      y_ref_ = y_ + (0.5 * h) * mask_.cwiseProduct(f_);
      y_new_ = y_ref_;
      sys.dissipate(t_, 0.5 * h, y_, y_new_);
      fd_ = (2.0 / h) * (y_new_ - y_ref_);
    }
    fd_prev_ = fd_;
    if (metric_) {
      double k_net = 0.0, k_gap = 0.0;
      net_terms(sys, f_, fd_, &k_net, &k_gap);
      // Before the first step T_net is taken on the rung's step (no switch yet).
      if (h_last_ == 0.0) {
        h_last_ = h_fixed_ / substeps_;
      } else {
        offset_ += 0.25 * h_last_ * h_last_ * (k_net_ - k_net);
      }
      k_net_ = k_net;
      k_gap_ = k_gap;
    }
    ++counters_.rhs_evaluations;
  }

  StepStatus step(const OdeSystem& system, double t_limit) override {
    if (!(t_limit > t_)) return StepStatus::kOk;
    const MechanicalSystem& sys = &system == system_ ? *mechanical_ : take(system);
    if (remaining_ <= 0 || t_limit < t_grid_ - 1e-9 * h_fixed_) {
      // A new grid step (or the caller moved t_limit inside the current one): its end, on
      // the grid relative to the last base point (no accumulated round-off) or at t_limit.
      t_grid_ = t_base_ + static_cast<double>(steps_since_base_ + 1) * h_fixed_;
      last_ = t_grid_ >= t_limit - 1e-9 * h_fixed_;
      if (last_) t_grid_ = t_limit;
      // A grid step cut short takes as many sub-steps of the current rung as fit.
      const double fit = std::ceil((t_grid_ - t_) / (h_fixed_ / substeps_) - 1e-9);
      remaining_ = static_cast<int>(std::clamp(fit, 1.0, static_cast<double>(substeps_)));
    }
    double dissipated = 0.0, h = 0.0, k_net = 0.0, k_gap = 0.0;
    start_ = {k_net_, k_gap_, h_last_, offset_, dissipated_, 0.0};
    for (;;) {
      double t_new = remaining_ <= 1 ? t_grid_ : t_ + (t_grid_ - t_) / remaining_;
      if (!(t_new > t_)) {  // sub-steps below the resolution of t: the rest in one
        t_new = t_grid_;
        remaining_ = 1;
      }
      h = t_new - t_;
      if (!(h > 0.0)) return StepStatus::kStepSizeCollapse;
      dissipated = kick_drift_kick(sys, y_, f_, t_, h, t_new);
      if (!new_point_finite()) {
        ++counters_.steps_rejected;
        return StepStatus::kNonFinite;
      }
      if (!metric_) break;
      net_terms(sys, f_new_, fd_new_, &k_net, &k_gap);
      const double term = 0.25 * h * h * k_net;
      if (!(budget_ > 0.0) || !(term > budget_) || substeps_ >= kMaxSubsteps || h <= h_min_) {
        break;
      }
      // Too large: retry the rest of the grid step on the finer rung that brings the term
      // to half the budget.
      ++counters_.steps_rejected;
      const int finer = rung(substeps_ * std::sqrt(term / (0.5 * budget_)));
      remaining_ *= finer / substeps_;
      grid_steps_at_rung_ = 0;
      substeps_ = finer;
    }
    accept(sys, h, dissipated, k_net, k_gap);
    start_.t_end = t_;
    if (--remaining_ > 0) return StepStatus::kOk;
    // At the grid point: the next grid step's rung.
    // (T_net on the rung's step: the last sub-step may have been cut short.)
    if (budget_ > 0.0) {
      const double hr = h_fixed_ / substeps_;
      next_rung(0.25 * hr * hr * k_net_);
    }
    if (last_) {
      t_base_ = t_;
      steps_since_base_ = 0;
    } else {
      ++steps_since_base_;
    }
    return StepStatus::kOk;
  }

  bool can_retake() const override { return true; }

  /// The grid step from the next reset() on (ode::set_verlet_step).
  void set_grid_step(double h) { h_fixed_ = h; }

  /// The last step again from its start, cut short at t (or stretched up to its first length):
  /// one step of t - t_prev(), booked as step() books it, from the bookkeeping the step started
  /// with. The grid restarts at the reset() that follows.
  bool retake(const OdeSystem& system, double t) override {
    if (!(t > t_prev_ && t <= start_.t_end)) return false;
    if (t == t_) return true;
    const MechanicalSystem& sys = &system == system_ ? *mechanical_ : take(system);
    const double h = t - t_prev_;
    const double dissipated = kick_drift_kick(sys, y_prev_, f_prev_, t_prev_, h, t);
    if (!new_point_finite()) return false;
    double k_net = 0.0, k_gap = 0.0;
    if (metric_) net_terms(sys, f_new_, fd_new_, &k_net, &k_gap);
    y_ = y_prev_;
    f_ = f_prev_;
    kick_ = kick_prev_;
    fd_ = fd_prev_;
    t_ = t_prev_;
    k_net_ = start_.k_net;
    k_gap_ = start_.k_gap;
    h_last_ = start_.h_last;
    offset_ = start_.offset;
    dissipated_ = start_.dissipated;
    --counters_.steps_accepted;  // the step is replaced, not added (accept() counts it)
    accept(sys, h, dissipated, k_net, k_gap);
    remaining_ = 0;
    return true;
  }

  /// Makes the step in y_new_, f_new_, fd_new_ (size h, ending at t_new_) the current one and
  /// books it: the dissipated energy, T_net's terms k_net, k_gap at its end, the switching
  /// offset at its start.
  void accept(const MechanicalSystem& sys, double h, double dissipated, double k_net,
              double k_gap) {
    // dq/dt at the final momenta (dense output and the record of f).
    sys.position_rate(y_new_, f_new_);

    // Booking with the net force: the split's exact booking makes E - T + D constant with T
    // the kicks' forces' term, so a foot held by friction against a spring (kick force F,
    // dissipative force -F, no motion) books the changes of h^2 |F|^2 / 8m as dissipation.
    // Moving the difference of the two terms at the step's ends from D to T (it telescopes)
    // leaves E - T_net + D constant instead, T_net = sum h^2 |F + a F_d|^2 / 8m with F_d the
    // closing half step's mean dissipative force: zero for a held foot, T in free motion.
    if (metric_) dissipated -= 0.25 * h * h * (k_gap - k_gap_);
    // A step size other than the last one's (a rung switch, a refined retry, a grid step cut
    // short at t_limit) changes the invariant by T_net(h_last) - T_net(h) at the start point.
    if (metric_) offset_ += 0.25 * (h_last_ * h_last_ - h * h) * k_net_;

    y_prev_.swap(y_);
    y_.swap(y_new_);
    f_prev_.swap(f_);
    f_.swap(f_new_);
    kick_prev_.swap(kick_);
    kick_.swap(kick_new_);
    fd_prev_.swap(fd_);
    fd_.swap(fd_new_);
    t_prev_ = t_;
    t_ = t_new_;
    opened_relaxed_ = relaxed_;
    dissipated_ += dissipated;
    k_net_ = k_net;
    k_gap_ = k_gap;
    h_last_ = h;
    ++counters_.steps_accepted;
  }

  /// Cubic Hermite on the step; with the dissipation split the momentum slopes include the
  /// mean dissipative forces, so the interpolant follows the damped momenta (an event located
  /// inside a step of a foot held by friction restarts from consistent momenta).
  void dense(double t, Vec& y_out) const override {
    if (!split_) {
      hermite_dense(t, t_prev_, t_, y_prev_, f_prev_, y_, f_, y_out);
      return;
    }
    slope_a_ = f_prev_ + fd_prev_;
    slope_b_ = f_ + fd_;
    hermite_dense(t, t_prev_, t_, y_prev_, slope_a_, y_, slope_b_, y_out);
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override { return h_fixed_ / substeps_; }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }
  const VerletInfo* verlet_info() const override { return this; }
  bool books_dissipation() const override { return split_; }
  double booked_dissipation() const override { return dissipated_; }
  double verlet_term() const override { return 0.25 * h_last_ * h_last_ * k_net_; }
  double switching_offset() const override { return offset_; }
  const Vec& opening_state() const override { return opened_relaxed_ ? y_start_ : kick_prev_; }
  const Vec& closing_state() const override { return kick_; }

 private:
  /// One Verlet step of size h from (t0, y0) with the kicks' force f0 there to t_new into
  /// y_new_, f_new_ (the kicks' forces at the new point in the momentum entries) and fd_new_
  /// (the closing half step's mean dissipative force); returns the energy the dissipation
  /// split removed [J]. Leaves the accepted state untouched.
  double kick_drift_kick(const MechanicalSystem& sys, const Vec& y0, const Vec& f0, double t0,
                         double h, double t_new) {
    t_new_ = t_new;
    double dissipated = 0.0;
    // First-order states relax first, at the step's start (MechanicalSystem::relax; its
    // energy booked by the system), so both kicks read the same potential: relaxing between
    // the kicks makes the kicks' work differ from the potential's change by half the relaxed
    // force times the step's displacement, an error of first order in h.
    const Vec* ys = &y0;
    const Vec* fs = &f0;
    relaxed_ = false;
    if (relax_) {
      y_start_ = y0;
      bool moved = false;
      dissipated += sys.relax(h, y_start_, &moved);
      if (moved || !(y_start_.array() == y0.array()).all()) {
        forces(sys, t0, y_start_, f_start_);
        ++counters_.rhs_evaluations;
        ys = &y_start_;
        fs = &f_start_;
        relaxed_ = true;
      }
    }
    // Kick: p_half = p + h/2 F(q, p); positions unchanged. With the split, the dissipative
    // forces follow at fixed positions, implicitly: together a backward Euler half step of
    // the momenta, so the positions drift with damped momenta.
    y_new_.noalias() = *ys + (0.5 * h) * mask_.cwiseProduct(*fs);
    if (split_) dissipated += sys.dissipate(t0, 0.5 * h, *ys, y_new_);
    // Drift: q_new = q + h G(p_half) (or the system's own flow, MechanicalSystem::drift).
    if (drift_) {
      sys.drift(h, y_new_);
    } else {
      sys.position_rate(y_new_, f_new_);
      y_new_.noalias() += h * q_mask_.cwiseProduct(f_new_);
    }
    // Closing kick with F at the new positions and the predicted momentum p*.
    p_half_ = y_new_;
    y_new_.noalias() += (0.5 * h) * mask_.cwiseProduct(*fs);
    forces(sys, t_new, y_new_, f_new_);
    kick_new_ = y_new_;  // (the point f_new_ is read at: the predicted momentum)
    ++counters_.rhs_evaluations;
    y_new_.noalias() = p_half_ + (0.5 * h) * mask_.cwiseProduct(f_new_);
    if (split_) {
      y_ref_ = y_new_;
      dissipated += sys.dissipate(t_new, 0.5 * h, y_ref_, y_new_);
      fd_new_ = (2.0 / h) * (y_new_ - y_ref_);
      sys.correct_step(*ys, y_new_);
    } else {
      fd_new_.setZero();
    }
    return dissipated;
  }

  /// True when the step in y_new_, f_new_ is finite (x * 0 is 0 for a finite x and NaN
  /// otherwise: one vectorised pass per vector).
  bool new_point_finite() const {
    return std::isfinite((y_new_.array() * 0.0).sum() + (f_new_.array() * 0.0).sum());
  }

  /// The net force f + a fd per momentum block (a mass's three components; see
  /// MechanicalSystem::momentum_block), a in [0, 1] making |f + a fd| as small as the dissipative
  /// force fd allows: fd cancels the part of f it holds (friction holding a foot against a
  /// spring) and is ignored where it acts along f (a damper stopping an impact). Position
  /// entries of the result are not used.
  void held_force(const Vec& f, const Vec& fd, Vec& out) const {
    out = f;
    const Eigen::Index n = f.size();
    auto held = [&](auto fb, auto db, auto ob) {
      const double dd = db.squaredNorm();
      const double a = dd > 0.0 ? std::clamp(-fb.dot(db) / dd, 0.0, 1.0) : 0.0;
      ob += a * db;
    };
    for (Eigen::Index i = 0; i + block_ <= n;) {
      if (mask_[i] == 0.0) {
        ++i;
        continue;
      }
      if (block_ == 3) {  // (fixed size: the mechanisms' blocks)
        held(f.segment<3>(i), fd.segment<3>(i), out.segment<3>(i));
      } else {
        held(f.segment(i, block_), fd.segment(i, block_), out.segment(i, block_));
      }
      i += block_;
    }
  }

  /// The kinetic energies [N^2/kg] of the held force f + a fd (*k_net; T_net = h^2/4 of it) and
  /// of f alone minus that (*k_gap) at a point with kicks' force f and dissipative force fd.
  void net_terms(const MechanicalSystem& sys, const Vec& f, const Vec& fd, double* k_net,
                 double* k_gap) {
    if ((fd.array() == 0.0).all()) {  // nothing dissipative acted: T_net = T
      *k_net = sys.kinetic_energy(f);
      *k_gap = 0.0;
      return;
    }
    held_force(f, fd, work_);
    *k_net = sys.kinetic_energy(work_);
    *k_gap = sys.kinetic_energy(f) - *k_net;
  }

  /// Chooses the rung of the next grid step at a grid point whose T_net on the current rung
  /// is `term` [J]; a switch from k to k' sub-steps changes E - T_net + D by
  /// term (1 - (k / k')^2).
  void next_rung(double term) {
    auto jump = [&](int k) {
      const double r = static_cast<double>(substeps_) / k;
      return term * (1.0 - r * r);
    };
    const int up = rung(std::sqrt(term / (kUp * budget_)) * substeps_);
    if (up > substeps_) {
      substeps_ = up;
      grid_steps_at_rung_ = 0;
      return;
    }
    ++grid_steps_at_rung_;
    const double small =
        kDown * budget_ * std::max(1.0, static_cast<double>(grid_steps_at_rung_) / kPatience);
    for (int k = 1; k < substeps_; k *= 2) {
      const double j = jump(k);
      if (std::abs(offset_ + j) <= std::abs(offset_) || std::abs(j) <= small) {
        substeps_ = k;
        grid_steps_at_rung_ = 0;
        return;
      }
    }
  }

  /// The smallest power of two >= x, within [1, kMaxSubsteps].
  static int rung(double x) {
    int k = 1;
    while (k < kMaxSubsteps && static_cast<double>(k) < x) k *= 2;
    return k;
  }

  /// The kicks' forces: without the dissipative ones when the system splits them off.
  void forces(const MechanicalSystem& sys, double t, const Vec& y, Vec& f) const {
    if (split_) {
      sys.conservative_rhs(t, y, f);
    } else {
      sys.rhs(t, y, f);
    }
  }

  /// The one place the stepper takes its system (at reset(), and at a step() on another
  /// system than the last): a MechanicalSystem, or std::invalid_argument.
  const MechanicalSystem& take(const OdeSystem& system) {
    const auto* mechanical = dynamic_cast<const MechanicalSystem*>(&system);
    if (mechanical == nullptr) {
      throw std::invalid_argument(
          "method verlet needs a mechanical system (positions and momenta); use rk4 or dopri5");
    }
    system_ = &system;
    mechanical_ = mechanical;
    return *mechanical;
  }

  /// Most sub-steps of one grid step (verlet_energy_budget); beyond it the budget is not kept.
  static constexpr int kMaxSubsteps = 4096;
  /// Budget fractions: a grid point refines when T_net exceeds kUp of the budget; a
  /// coarsening switch is small when it changes E - T_net + D by at most kDown of it (a limit
  /// that grows in proportion after kPatience grid steps on one rung). Chosen on the quad
  /// hopper drop: kDown 0.02 ... 0.1 all keep the sampled balance near the budget.
  static constexpr double kUp = 1.0;
  static constexpr double kDown = 0.05;
  static constexpr int kPatience = 20;

  /// The bookkeeping at the start of the last accepted step (retake() restores it).
  struct StepStart {
    double k_net = 0.0, k_gap = 0.0, h_last = 0.0, offset = 0.0, dissipated = 0.0;
    double t_end = 0.0;  ///< the step's end as step() took it [s]
  };

  double h_fixed_;             ///< nominal step, the grid step with an energy budget [s]
  double budget_;              ///< bound on Verlet's bounded energy term per sub-step [J]
  double h_min_;               ///< no sub-step below this [s]
  int substeps_ = 1;           ///< sub-steps of the current (or next) grid step
  int remaining_ = 0;          ///< sub-steps left in the current grid step (0: none begun)
  double t_ = 0.0;             ///< current time [s]
  double t_prev_ = 0.0;        ///< start of the last accepted step [s]
  double t_new_ = 0.0;         ///< end of the step in y_new_ [s]
  double t_base_ = 0.0;        ///< time the step grid counts from [s]
  double t_grid_ = 0.0;        ///< end of the current grid step [s]
  bool last_ = false;          ///< the current grid step ends at the caller's t_limit
  long steps_since_base_ = 0;  ///< grid steps taken on the current grid
  Vec y_, y_prev_, y_new_;
  Vec f_, f_prev_, f_new_;           ///< f at t_, t_prev_ and the new point
  Vec fd_, fd_new_;                  ///< mean dissipative force of the closing half step [N]
  Vec fd_prev_;                      ///< fd_ at t_prev_ [N]
  mutable Vec slope_a_, slope_b_;    ///< dense(): the momentum slopes with the dissipation
  Vec kick_, kick_prev_, kick_new_;  ///< the points f_, f_prev_, f_new_ were read at
  Vec p_half_;                       ///< state after the drift (momenta at the half step)
  Vec y_ref_;                        ///< split: the state before the closing dissipative update
  Vec y_start_, f_start_;            ///< relax: the step's start after the relaxation, its forces
  Vec work_;                         ///< scratch: the net force
  Vec mask_;                         ///< 1 on momentum states, 0 on positions
  Vec q_mask_;                       ///< 1 - mask_
  bool split_ = false;               ///< the system's dissipation split is applied
  bool drift_ = false;               ///< the system drifts its positions itself
  bool relax_ = false;               ///< the system relaxes first-order states at the step start
  bool relaxed_ = false;             ///< the step in y_new_ opened from y_start_, f_start_
  bool opened_relaxed_ = false;      ///< ... the accepted one (opening_state())
  int block_ = 1;                    ///< momentum entries per rotation block
  bool metric_ = false;              ///< T_net is tracked (a metric, and a split or a budget)
  double k_net_ = 0.0;               ///< kinetic energy of the held force at t_ [N^2/kg]
  double k_gap_ = 0.0;          ///< kinetic energy of the kicks' force minus k_net_ at t_ [N^2/kg]
  int grid_steps_at_rung_ = 0;  ///< grid steps taken since the rung last changed
  double h_last_ = 0.0;         ///< size of the last accepted step [s]
  double offset_ = 0.0;         ///< accumulated change of E - T_net + D at step-size switches [J]
  double dissipated_ = 0.0;     ///< energy the dissipative halves removed [J]
  StepStart start_;             ///< the last accepted step's start
  SolverCounters counters_;
  const OdeSystem* system_ = nullptr;             ///< the system of the last take()
  const MechanicalSystem* mechanical_ = nullptr;  ///< ... as a mechanical system
};

}  // namespace

std::unique_ptr<Stepper> make_verlet_stepper(const SolverOptions& options, int n) {
  return std::make_unique<VerletStepper>(options, n);
}

}  // namespace pronk::ode::detail

namespace pronk::ode {

bool set_verlet_step(Stepper& stepper, double h) {
  auto* verlet = dynamic_cast<detail::VerletStepper*>(&stepper);
  if (verlet == nullptr || !(h > 0.0)) return false;
  verlet->set_grid_step(h);
  return true;
}

}  // namespace pronk::ode
