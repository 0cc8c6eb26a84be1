// Method verlet's energy bookkeeping, beyond the Stepper interface.
#pragma once

#include "sim/ode/solver.hpp"

namespace pronk::ode {

/// What the symplectic stepper (method verlet, on a MechanicalSystem) reports beyond
/// Stepper: Stepper::verlet_info() returns it for that stepper, null for the others.
/// energy - verlet_term() + booked_dissipation() - switching_offset() is constant for
/// quadratic potentials (docs/pseudorigid.md, "Solver: velocity Verlet").
class VerletInfo {
 public:
  /// True when the stepper applies the system's dissipation split
  /// (MechanicalSystem::dissipate): the energy it removed is then booked_dissipation(), not
  /// an integral of a power.
  virtual bool books_dissipation() const = 0;
  /// Energy the dissipative updates removed since the stepper was made [J] (not reset by
  /// reset()).
  virtual double booked_dissipation() const = 0;
  /// With a kinetic-energy metric (MechanicalSystem::kinetic_energy) and a dissipation split
  /// or an energy budget: the bounded term at the current point,
  /// T_net = sum h^2 |F + a F_d|^2 / 8 m [J]; 0 otherwise.
  virtual double verlet_term() const = 0;
  /// The accumulated change of the invariant at step-size switches and restarts [J].
  virtual double switching_offset() const = 0;
  /// The points the last accepted step's kicks read their forces at. Opening: the step's
  /// start after the system's relaxation (MechanicalSystem::relax), or else the last closing
  /// point (a restart's: its state). Closing: the positions at t() with the predicted momenta,
  /// where velocity-dependent forces are read. A work booked with forces read elsewhere is not
  /// the work the kicks did.
  virtual const Vec& opening_state() const = 0;
  virtual const Vec& closing_state() const = 0;

 protected:
  ~VerletInfo() = default;
};

/// Method verlet: h [s] becomes the grid step from the next reset() on (a run whose stiff
/// modes come and go takes each phase at its own step; the change of Verlet's bounded term
/// enters the switching offset as any step-size switch). False, changing nothing, for the
/// other methods.
bool set_verlet_step(Stepper& stepper, double h);

/// True when stepper books the dissipated energy itself (VerletInfo::books_dissipation).
inline bool books_dissipation(const Stepper& stepper) {
  const VerletInfo* v = stepper.verlet_info();
  return v != nullptr && v->books_dissipation();
}
/// The energy stepper booked as dissipated [J]; 0 for a stepper without the bookkeeping.
inline double booked_dissipation(const Stepper& stepper) {
  const VerletInfo* v = stepper.verlet_info();
  return v != nullptr ? v->booked_dissipation() : 0.0;
}

}  // namespace pronk::ode
