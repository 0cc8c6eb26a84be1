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
