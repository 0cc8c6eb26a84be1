// Velocity Verlet (Stormer-Verlet, kick-drift-kick) for mechanical systems
// y = (q, p), dq/dt = G(p), dp/dt = F(t, q, p): fixed step, order 2, symplectic
// and time-reversible when F does not depend on p, so a conservative mechanism's
// energy error stays bounded (O((omega h)^2) for its fastest mode omega) instead
// of drifting; linear and angular momentum are conserved exactly for pairwise
// central forces. One full RHS per step (F at the new positions is also the
// first kick of the next step) plus two cheap position_rate() calls.
//
// Systems with a dissipation split (OdeSystem::dissipate) take their dissipative
// forces out of the kicks: each half kick of the other forces is followed by the
// dissipative forces over h/2 at fixed positions, solved implicitly by the system, so
// each half kick is a backward Euler step of the momenta (a Strang splitting with the
// dissipation before the kicks let an undamped kick move a stuck foot: the creep and
// the dissipation came out hc/2m times too large). Stiff dampers and regularised
// friction then cost no stability (the step is limited by the springs alone), a creep
// under a constant force has the exact speed F/c, the dissipated energy is booked so
// that E - T + booked dissipation is exactly constant for quadratic potentials
// (booked_dissipation(); T = sum h^2 |F|^2 / 8m, Verlet's bounded term), and without
// dissipation the method is Verlet; the dissipation itself is first order. The dense
// output's slopes are then those of the kicks' forces (without the dissipative ones).
//
// Otherwise velocity-dependent forces (dampers, friction, drag) make the closing
// kick implicit in p; it is made explicit by evaluating F at the predicted momentum
// p* = p_half + h/2 F_n, which keeps the method second order for them (it is no
// longer symplectic then; nothing dissipative is).
//
// Stable for h < 2 / omega_max of the springs (and, without the split, of the
// dampers); beyond that the energy grows without bound, and the callers'
// divergence monitors end the run.
#include <cassert>
#include <stdexcept>

#include "sim/ode/steppers.hpp"

namespace pronk::ode::detail {
namespace {

class VerletStepper final : public Stepper {
 public:
  VerletStepper(const SolverOptions& options, int n)
      : h_fixed_(options.h_fixed),
        y_(Vec::Zero(n)),
        y_prev_(Vec::Zero(n)),
        y_new_(Vec::Zero(n)),
        f_(Vec::Zero(n)),
        f_prev_(Vec::Zero(n)),
        f_new_(Vec::Zero(n)),
        p_half_(Vec::Zero(n)),
        y_ref_(Vec::Zero(n)),
        mask_(Vec::Zero(n)),
        q_mask_(Vec::Zero(n)) {}

  void reset(const OdeSystem& sys, double t, const Vec& y) override {
    assert(y.size() == y_.size());
    if (!sys.has_mechanical_split()) {
      throw std::invalid_argument(
          "method verlet needs a mechanical system (positions and momenta); use rk4 or dopri5");
    }
    sys.momentum_mask(mask_);
    split_ = sys.has_dissipation_split();
    q_mask_ = Vec::Ones(mask_.size()) - mask_;
    t_ = t;
    t_prev_ = t;
    t_base_ = t;
    steps_since_base_ = 0;
    y_ = y;
    y_prev_ = y;
    forces(sys, t_, y_, f_);
    f_prev_ = f_;
    ++counters_.rhs_evaluations;
  }

  StepStatus step(const OdeSystem& sys, double t_limit) override {
    if (!(t_limit > t_)) return StepStatus::kOk;
    // Grid time relative to the last base point avoids accumulating round-off.
    double t_new = t_base_ + static_cast<double>(steps_since_base_ + 1) * h_fixed_;
    const bool last = t_new >= t_limit - 1e-9 * h_fixed_;
    if (last) t_new = t_limit;
    const double h = t_new - t_;
    if (!(h > 0.0)) return StepStatus::kStepSizeCollapse;

    double dissipated = 0.0;
    // Kick: p_half = p + h/2 F(q, p); positions unchanged. With the split, the dissipative
    // forces follow at fixed positions, implicitly: together a backward Euler half step of
    // the momenta, so the positions drift with damped momenta.
    y_new_.noalias() = y_ + (0.5 * h) * mask_.cwiseProduct(f_);
    if (split_) dissipated += sys.dissipate(t_, 0.5 * h, y_, y_new_);
    // Drift: q_new = q + h G(p_half).
    sys.position_rate(y_new_, f_new_);
    y_new_.noalias() += h * q_mask_.cwiseProduct(f_new_);
    // Closing kick with F at the new positions and the predicted momentum p*.
    p_half_ = y_new_;
    y_new_.noalias() += (0.5 * h) * mask_.cwiseProduct(f_);
    forces(sys, t_new, y_new_, f_new_);
    ++counters_.rhs_evaluations;
    y_new_.noalias() = p_half_ + (0.5 * h) * mask_.cwiseProduct(f_new_);
    if (split_) {
      y_ref_ = y_new_;
      dissipated += sys.dissipate(t_new, 0.5 * h, y_ref_, y_new_);
      sys.correct_step(y_, y_new_);
    }
    if (!y_new_.allFinite() || !f_new_.allFinite()) {
      ++counters_.steps_rejected;
      return StepStatus::kNonFinite;
    }
    // dq/dt at the final momenta (dense output and the record of f).
    sys.position_rate(y_new_, f_new_);

    y_prev_.swap(y_);
    y_.swap(y_new_);
    f_prev_.swap(f_);
    f_.swap(f_new_);
    t_prev_ = t_;
    t_ = t_new;
    dissipated_ += dissipated;
    if (last) {
      t_base_ = t_;
      steps_since_base_ = 0;
    } else {
      ++steps_since_base_;
    }
    ++counters_.steps_accepted;
    return StepStatus::kOk;
  }

  void dense(double t, Vec& y_out) const override {
    hermite_dense(t, t_prev_, t_, y_prev_, f_prev_, y_, f_, y_out);
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override { return h_fixed_; }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }
  bool books_dissipation() const override { return split_; }
  double booked_dissipation() const override { return dissipated_; }

 private:
  /// The kicks' forces: without the dissipative ones when the system splits them off.
  void forces(const OdeSystem& sys, double t, const Vec& y, Vec& f) const {
    if (split_) {
      sys.conservative_rhs(t, y, f);
    } else {
      sys.rhs(t, y, f);
    }
  }

  double h_fixed_;             ///< nominal step [s]
  double t_ = 0.0;             ///< current time [s]
  double t_prev_ = 0.0;        ///< start of the last accepted step [s]
  double t_base_ = 0.0;        ///< time the step grid counts from [s]
  long steps_since_base_ = 0;  ///< steps taken on the current grid
  Vec y_, y_prev_, y_new_;
  Vec f_, f_prev_, f_new_;   ///< f at t_, t_prev_ and the new point
  Vec p_half_;               ///< state after the drift (momenta at the half step)
  Vec y_ref_;                ///< split: the state before the closing dissipative update
  Vec mask_;                 ///< 1 on momentum states, 0 on positions
  Vec q_mask_;               ///< 1 - mask_
  bool split_ = false;       ///< the system's dissipation split is applied
  double dissipated_ = 0.0;  ///< energy the dissipative halves removed [J]
  SolverCounters counters_;
};

}  // namespace

std::unique_ptr<Stepper> make_verlet_stepper(const SolverOptions& options, int n) {
  return std::make_unique<VerletStepper>(options, n);
}

}  // namespace pronk::ode::detail
