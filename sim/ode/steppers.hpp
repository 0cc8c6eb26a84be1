// Internal factories of the concrete steppers behind make_stepper().
#pragma once

#include <memory>

#include "sim/ode/solver.hpp"

namespace pronk::ode::detail {

/// Euler, RK2 midpoint or RK4 with fixed step options.h_fixed [s] and cubic
/// Hermite dense output. options.method must be a fixed-step method.
std::unique_ptr<Stepper> make_explicit_rk_stepper(const SolverOptions& options, int n);

/// Dormand-Prince 5(4) with error control, FSAL and Hairer's dense output.
std::unique_ptr<Stepper> make_dopri5_stepper(const SolverOptions& options, int n);

/// RODAS4 Rosenbrock method with error control and dense output.
std::unique_ptr<Stepper> make_rodas4_stepper(const SolverOptions& options, int n);

/// RADAU5 (Radau IIA, order 5) with simplified Newton, error control and dense output.
std::unique_ptr<Stepper> make_radau5_stepper(const SolverOptions& options, int n);

/// Velocity Verlet with fixed step options.h_fixed [s] and cubic Hermite dense output;
/// reset() throws std::invalid_argument for a system without a mechanical split.
std::unique_ptr<Stepper> make_verlet_stepper(const SolverOptions& options, int n);

}  // namespace pronk::ode::detail
