// Internal factories of the concrete steppers behind make_stepper().
#pragma once

#include <memory>

#include "sim/ode/error_norm.hpp"
#include "sim/ode/solver.hpp"

namespace pronk::ode::detail {

/// Cubic Hermite interpolation at t on the step [t0, t1] through (y0, f0) and (y1, f1)
/// (the dense output of the fixed-step methods); y_out = y1 when the step is empty.
inline void hermite_dense(double t, double t0, double t1, const Vec& y0, const Vec& f0,
                          const Vec& y1, const Vec& f1, Vec& y_out) {
  const double h = t1 - t0;
  y_out.resize(y1.size());
  if (!(h > 0.0)) {
    y_out = y1;
    return;
  }
  const double s = (t - t0) / h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  y_out.noalias() = (2.0 * s3 - 3.0 * s2 + 1.0) * y0 + ((s3 - 2.0 * s2 + s) * h) * f0 +
                    (-2.0 * s3 + 3.0 * s2) * y1 + ((s3 - s2) * h) * f1;
}

/// Euler, RK2 midpoint or RK4 with fixed step options.h_fixed [s] and cubic
/// Hermite dense output. options.method must be a fixed-step method.
std::unique_ptr<Stepper> make_explicit_rk_stepper(const SolverOptions& options, int n);

/// Dormand-Prince 5(4) with error control, FSAL and Hairer's dense output.
std::unique_ptr<Stepper> make_dopri5_stepper(const SolverOptions& options, int n, ErrorNorm norm);

/// RODAS4 Rosenbrock method with error control and dense output.
std::unique_ptr<Stepper> make_rodas4_stepper(const SolverOptions& options, int n, ErrorNorm norm);

/// RADAU5 (Radau IIA, order 5) with simplified Newton, error control and dense output.
std::unique_ptr<Stepper> make_radau5_stepper(const SolverOptions& options, int n, ErrorNorm norm);

/// SUNDIALS CVODE BDF (sim/ode/cvode.cpp): the system's analytic Jacobian with KLU or dense
/// LU; a scaled norm's per-state atol.
std::unique_ptr<Stepper> make_cvode_stepper(const SolverOptions& options, int n, ErrorNorm norm);

/// Velocity Verlet with fixed step options.h_fixed [s] and cubic Hermite dense output;
/// reset() throws std::invalid_argument for a system that is not an ode::MechanicalSystem.
std::unique_ptr<Stepper> make_verlet_stepper(const SolverOptions& options, int n);

}  // namespace pronk::ode::detail
