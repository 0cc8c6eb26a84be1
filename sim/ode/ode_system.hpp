// The first-order ODE system dy/dt = f(t, y) that every solver integrates.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace pronk::ode {

using Vec = Eigen::VectorXd;

/// A first-order ODE system dy/dt = f(t, y). Implementations are cheap adapters
/// that hold a const model and the run's phase data (e.g. the leg forces of the
/// current stance); `rhs` must not allocate and must be deterministic.
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  /// Number of states.
  virtual int dimension() const = 0;
  /// Writes f(t, y) into dydt (already sized to dimension()).
  virtual void rhs(double t, const Vec& y, Vec& dydt) const = 0;

  /// Optional analytic Jacobian df/dy for the implicit (Rosenbrock) stepper.
  /// Without it the stepper uses forward differences (n extra RHS evaluations).
  virtual bool has_jacobian() const { return false; }
  /// Writes df/dy at (t, y) into J (resized to n x n by the callee).
  virtual void jacobian(double /*t*/, const Vec& /*y*/, Eigen::SparseMatrix<double>& /*J*/) const {}
  /// True when f does not depend on t explicitly (the Rosenbrock stepper then
  /// skips the df/dt term; otherwise it estimates df/dt by a forward difference).
  virtual bool autonomous() const { return false; }

  /// Optional mechanical structure for the symplectic stepper ("verlet"): the states split
  /// into positions q and momenta p with dq/dt = G(p) depending on the momenta only (not on q
  /// or t) and dp/dt = F(t, q, p), the rest of f.
  virtual bool has_mechanical_split() const { return false; }
  /// Writes 1 for momentum states and 0 for position states into mask (sized dimension()).
  virtual void momentum_mask(Vec& /*mask*/) const {}
  /// Writes G(p) into the position entries of dydt; leaves its momentum entries unchanged.
  /// Must be much cheaper than rhs() (the stepper calls it twice per step).
  virtual void position_rate(const Vec& /*y*/, Vec& /*dydt*/) const {}
  /// Optional, with the mechanical split: the kinetic energy 1/2 p^T M^-1 p [J] of the
  /// momentum entries of y (positions ignored), the metric of Verlet's bounded energy term
  /// T = h^2 / 4 kinetic_energy(F) (F in the momentum entries) that
  /// SolverOptions::verlet_energy_budget keeps in bounds. Returns a negative number when
  /// the system has no such metric (the default).
  virtual double kinetic_energy(const Vec& /*y*/) const { return -1.0; }
  /// The momentum entries come in consecutive blocks of this many (a point mass's three
  /// Cartesian components) that belong together under rotations: the symplectic stepper's
  /// held-force projection acts per block, so it does not depend on the frame.
  virtual int momentum_block() const { return 1; }
  /// Optional, with the mechanical split: a drift of its own. Systems whose position rate
  /// also depends on the positions (a rigid body's attitude quaternion turns with
  /// omega = R I^-1 R^T L) advance the position entries of y over h [s] at fixed momenta by
  /// a symplectic flow of their kinetic energy; without it the stepper drifts q += h G(p).
  virtual bool has_drift() const { return false; }
  virtual void drift(double /*h*/, Vec& /*y*/) const {}

  /// Optional dissipation split for the symplectic stepper (needs the mechanical split): the
  /// velocity-dependent dissipative forces (dampers, friction, drag) leave the kicks and act
  /// as velocity-only updates at fixed positions, each solved implicitly, so stiff damping
  /// and regularised friction cost no stability, and the energy they remove is known exactly.
  virtual bool has_dissipation_split() const { return false; }
  /// dy/dt without the dissipative forces dissipate() applies (same layout as rhs()).
  virtual void conservative_rhs(double t, const Vec& y, Vec& dydt) const { rhs(t, y, dydt); }
  /// Applies the dissipative forces over a time h [s] to the momenta of y (positions fixed)
  /// and returns the energy to book as dissipated [J]: -sum dP . (v_ref + dP / 2 m) over the
  /// momentum changes dP, with v_ref the velocities of y_ref. The stepper passes as y_ref the
  /// state before the preceding kick for the first half of a step, and y itself (before the
  /// update) for the second: then E - T + booked dissipation is exactly constant for
  /// quadratic potentials, T = sum h^2 |F_j|^2 / 8 m_j the bounded Verlet term.
  virtual double dissipate(double /*t*/, double /*h*/, const Vec& /*y_ref*/, Vec& /*y*/) const {
    return 0.0;
  }
  /// With the dissipation split, after each step from y0 to y1: a potential that is only
  /// piecewise quadratic (one-sided contact) breaks the exact balance above in a step that
  /// crosses its kink (a foot landing at 1.7 m/s on a 1e5 N/m ground lost up to 0.03 J per
  /// touchdown at h = 5e-4 s); the system may correct the momenta of y1 so that the step's
  /// energy change is the exact one.
  virtual void correct_step(const Vec& /*y0*/, Vec& /*y1*/) const {}
};

/// A scalar event function g(t, y); an event fires when g crosses zero in the
/// requested direction during a step.
class EventFunction {
 public:
  virtual ~EventFunction() = default;
  virtual double value(double t, const Vec& y) const = 0;
  /// -1: only falling crossings (g goes from > 0 to <= 0); +1: only rising; 0: both.
  virtual int direction() const { return -1; }
};

}  // namespace pronk::ode
