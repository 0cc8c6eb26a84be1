// The robot run's step observer: energy flows (Verlet's own booking, or Gauss-Legendre on the
// dense output), monitors and samples along the accepted steps.
#pragma once

#include <algorithm>
#include <cmath>

#include "sim/ode/verlet.hpp"
#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/robot/run_monitor.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Vector3d;

/// Energy flows, monitors and samples along the accepted steps. Method verlet books both
/// flows as its steps do: the dissipation is the stepper's own (MechanicalSystem::dissipate),
/// the actuator work 1/2 (A_a + A_b) . (x_b - x_a) over the masses with the actuator forces A
/// read where the step's kicks read them (VerletInfo::opening_state, closing_state: after the
/// feet's relaxation, and at the predicted momenta, where the stance feedback's damping term
/// is read), so that E - T + D - W is exact for quadratic potentials, T Verlet's bounded term
/// (docs/pseudorigid.md). Quasi-static feet only: with foot masses the forces are read at the
/// step's ends with the final momenta, an error of first order in h through the damping term
/// (pr_running, four masses, auto: 6.8e-4 of the scale against 5.1e-4 at the kicks' points),
/// kept until the committed designs, whose booked work and drift it moves, are recorded
/// again. Both flows are linear in time within a step. Other methods integrate
/// the dissipated and actuator power by Gauss-Legendre on the dense output. A sample inside a
/// step pairs its state with the flows up to the sample time.
class Observer final : public ode::StepObserver {
 public:
  Observer(RunMonitor& run, double interval, int n, bool verlet)
      : run_(run),
        interval_(interval),
        verlet_(verlet),
        yq_(n),
        ya_(n),
        fa_(run.sys.actuator_force_size()),
        fb_(run.sys.actuator_force_size()) {}
  void on_step(const ode::Stepper& st, double t_stop) override {
    const double ta = st.t_prev(), tb = t_stop;
    const double d_a = run_.dissipated, w_a = run_.work;
    double step_d = 0.0, step_w = 0.0;  // the whole step's flows (verlet) [J]
    if (verlet_) {
      const double booked = ode::booked_dissipation(st);
      step_d = booked - booked_;
      booked_ = booked;
      step_w = verlet_work(st);
    }
    flows(st, ta, tb, step_d, step_w, &run_.dissipated, &run_.work);
    run_.positive_work += std::max(0.0, run_.work - w_a);
    st.dense(tb, yq_);
    run_.monitor(yq_);
    while (next_ <= tb + 1e-12 * std::max(1.0, tb)) {
      const double ts = std::min(next_, tb);
      double d = d_a, w = w_a;
      flows(st, ta, ts, step_d, step_w, &d, &w);
      st.dense(ts, yq_);
      run_.sample(next_, yq_, d, w);
      next_ = interval_ * static_cast<double>(++count_);
    }
  }
  void start(const ode::Stepper& st, const ode::Vec& y) {
    booked_ = ode::booked_dissipation(st);
    run_.sample(0.0, y, run_.dissipated, run_.work);
    next_ = interval_ * static_cast<double>(++count_);
  }
  /// The stepper restarts (a new state or new actuator forces): the next step's start
  /// forces are evaluated afresh.
  void restart() { have_fa_ = false; }

 private:
  /// Adds the flows over [ta, te] of the current step (which ends at st.t()) to *d and *w;
  /// verlet: the fraction of the step's flows step_d, step_w [J].
  void flows(const ode::Stepper& st, double ta, double te, double step_d, double step_w, double* d,
             double* w) {
    if (verlet_) {
      const double frac = st.t() > ta ? (te - ta) / (st.t() - ta) : 1.0;
      *d += frac * step_d;
      *w += frac * step_w;
      return;
    }
    static const double s[3] = {0.5 - std::sqrt(15.0) / 10.0, 0.5, 0.5 + std::sqrt(15.0) / 10.0};
    static const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    for (int q = 0; q < 3; ++q) {
      st.dense(ta + s[q] * (te - ta), yq_);
      const double wq = gw[q] * (te - ta);
      const pr::PowerFlows p = run_.msys.power(yq_);
      *d += wq * p.dissipated;
      *w += wq * (p.actuator + run_.sys.actuator_power(yq_));
    }
  }

  /// Verlet's actuator work over its last step [J] (see the class comment); the forces at
  /// the step's end are kept for the next step's start.
  double verlet_work(const ode::Stepper& st) {
    // The points the kicks read the forces at (see the class comment); the foot masses' runs
    // read them at the step's ends with the final momenta, as the committed designs recorded.
    const ode::VerletInfo& vi = *st.verlet_info();
    const bool at_kicks = run_.sys.quasi_static();
    if (at_kicks) {
      const ode::Vec& y_open = vi.opening_state();
      // (the last closing point, unless a restart or the relaxation moved the feet since)
      if (!have_fa_ || !(y_open.array() == ya_.array()).all()) {
        ya_ = y_open;
        on_a_ = run_.sys.actuator_mass_forces(ya_, fa_);
      }
    } else if (!have_fa_) {
      st.dense(st.t_prev(), ya_);  // the step's start (the dense output's end point)
      on_a_ = run_.sys.actuator_mass_forces(ya_, fa_);
    }
    const ode::Vec& yb = at_kicks ? vi.closing_state() : st.y();
    const bool on_b = run_.sys.actuator_mass_forces(yb, fb_);
    double w = 0.0;
    const int nm = static_cast<int>(run_.model.mechanism.masses.size());
    for (int j = 0; j < nm; ++j) {
      Vector3d f = Vector3d::Zero();
      if (on_a_) f += fa_.segment<3>(3 * j);
      if (on_b) f += fb_.segment<3>(3 * j);
      w += 0.5 * f.dot(yb.segment<3>(6 * j) - ya_.segment<3>(6 * j));
    }
    const int r = run_.sys.rotation_state();
    if (r >= 0) {  // rigid body: the torque over the step's rotation (world rotation vector)
      Vector3d tau = Vector3d::Zero();
      if (on_a_) tau += fa_.segment<3>(3 * nm);
      if (on_b) tau += fb_.segment<3>(3 * nm);
      const Eigen::AngleAxisd turn(pr::rigid_quaternion(yb, r) *
                                   pr::rigid_quaternion(ya_, r).conjugate());
      w += 0.5 * tau.dot(turn.angle() * turn.axis());
    }
    ya_ = yb;
    fa_.swap(fb_);
    on_a_ = on_b;
    have_fa_ = true;
    return w;
  }

  RunMonitor& run_;
  double interval_;
  bool verlet_;
  ode::Vec yq_;
  ode::Vec ya_, fa_, fb_;  ///< verlet: the step's opening state and the actuator forces at its ends
  bool on_a_ = false;      ///< fa_ holds forces (actuators act at the step's start)
  bool have_fa_ = false;   ///< ya_ and fa_ are the current step's start
  double next_ = 0.0;
  long count_ = 0;
  double booked_ = 0.0;  ///< the stepper's booked dissipation at the end of the last step [J]
};
}  // namespace pronk::robot::detail
