// A mechanical ODE system: positions and momenta, for the symplectic stepper ("verlet").
#pragma once

#include "sim/ode/ode_system.hpp"

namespace pronk::ode {

/// An ODE system whose states split into positions q and momenta p with dq/dt = G(p)
/// depending on the momenta only (not on q or t) and dp/dt = F(t, q, p), the rest of f.
/// Method verlet integrates only these (make_stepper's verlet stepper refuses any other
/// system at reset()); rodas4 and radau5 factorise their Jacobians through the momentum
/// Schur complement (stiff_linear_algebra.hpp). The states may interleave (a mechanism's
/// (x_j, p_j) per mass): momentum_mask() says which are which. The design and its
/// measurements: docs/pseudorigid.md, "Solver: velocity Verlet".
class MechanicalSystem : public OdeSystem {
 public:
  /// Writes 1 for momentum states and 0 for position states into mask (sized dimension()).
  virtual void momentum_mask(Vec& mask) const = 0;
  /// Writes G(p) into the position entries of dydt; leaves its momentum entries unchanged.
  /// Must be much cheaper than rhs() (the stepper calls it twice per step).
  virtual void position_rate(const Vec& y, Vec& dydt) const = 0;

  /// Optional: the kinetic energy 1/2 p^T M^-1 p [J] of the momentum entries of y (positions
  /// ignored), the metric of Verlet's bounded energy term T = h^2 / 4 kinetic_energy(F) (F
  /// in the momentum entries) that SolverOptions::verlet_energy_budget bounds. Negative
  /// (the default): the system has no such metric.
  virtual double kinetic_energy(const Vec& /*y*/) const { return -1.0; }
  /// The momentum entries come in consecutive blocks of this many (a point mass's three
  /// Cartesian components) that belong together under rotations: the stepper's held-force
  /// projection acts per block, so it does not depend on the frame.
  virtual int momentum_block() const { return 1; }

  /// Optional drift of its own, for position rates that also depend on the positions (a
  /// rigid body's attitude quaternion turns with omega = R I^-1 R^T L): advances the
  /// position entries of y over h [s] at fixed momenta by a symplectic flow of the kinetic
  /// energy. Without it the stepper drifts q += h G(p).
  virtual bool has_drift() const { return false; }
  virtual void drift(double /*h*/, Vec& /*y*/) const {}

  /// Optional dissipation split: the velocity-dependent dissipative forces (dampers,
  /// friction, drag) leave the kicks and act as implicit velocity-only updates at fixed
  /// positions (dissipate()), and the energy they remove is booked exactly.
  virtual bool has_dissipation_split() const { return false; }
  /// dy/dt without the dissipative forces dissipate() applies (same layout as rhs()).
  virtual void conservative_rhs(double t, const Vec& y, Vec& dydt) const { rhs(t, y, dydt); }
  /// Applies the dissipative forces over a time h [s] to the momenta of y (positions fixed)
  /// and returns the energy to book as dissipated [J]: -sum dP . (v_ref + dP / 2 m) over the
  /// momentum changes dP, with v_ref the velocities of y_ref (the stepper passes the state
  /// before the preceding kick for a step's first half, y itself before the update for the
  /// second). E - T + booked dissipation is then exactly constant for quadratic potentials.
  virtual double dissipate(double /*t*/, double /*h*/, const Vec& /*y_ref*/, Vec& /*y*/) const {
    return 0.0;
  }
  /// Optional relaxation: states that are neither positions nor momenta (first-order states,
  /// e.g. a massless foot's ground position under a creep law) are advanced over h [s] at the
  /// step's start, at fixed positions and momenta, implicitly; both kicks then read forces on
  /// the relaxed states, so the step's work is that of one potential. Returns the energy to
  /// book as dissipated [J] (the potential energy the relaxation released at fixed positions);
  /// *forces_moved: whether it changed the forces on the positions.
  virtual bool has_relaxation() const { return false; }
  virtual double relax(double /*h*/, Vec& /*y*/, bool* forces_moved) const {
    *forces_moved = false;
    return 0.0;
  }
  /// With the dissipation split, after each step from y0 to y1: may correct the momenta of
  /// y1 so that the step's energy change is the exact one where a potential is only
  /// piecewise quadratic (one-sided contact) and the step crossed its kink.
  virtual void correct_step(const Vec& /*y0*/, Vec& /*y1*/) const {}
};

}  // namespace pronk::ode
