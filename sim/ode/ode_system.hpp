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

  /// Optional error norm of adaptive steppers. `err` is the local error estimate
  /// of a step from y0 to y1; the result is compared with 1 (<= 1: accept).
  /// Default (has_error_norm() false): the RMS of err_i / (atol + rtol max(|y0_i|, |y1_i|)).
  virtual bool has_error_norm() const { return false; }
  virtual double error_norm(const Vec& /*err*/, const Vec& /*y0*/, const Vec& /*y1*/,
                            double /*rtol*/, double /*atol*/) const {
    return 0.0;
  }

  /// Optional mechanical structure for the symplectic stepper ("verlet"): the states split
  /// into positions q and momenta p with dq/dt = G(p) depending on the momenta only (not on q
  /// or t) and dp/dt = F(t, q, p), the rest of f.
  virtual bool has_mechanical_split() const { return false; }
  /// Writes 1 for momentum states and 0 for position states into mask (sized dimension()).
  virtual void momentum_mask(Vec& /*mask*/) const {}
  /// Writes G(p) into the position entries of dydt; leaves its momentum entries unchanged.
  /// Must be much cheaper than rhs() (the stepper calls it twice per step).
  virtual void position_rate(const Vec& /*y*/, Vec& /*dydt*/) const {}
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
