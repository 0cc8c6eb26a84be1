// The error norm the adaptive solvers use on a mechanism (ode::ErrorNorm).
#pragma once

#include "sim/ode/error_norm.hpp"
#include "sim/pseudorigid/model.hpp"
#include "sim/pseudorigid/system.hpp"

namespace pronk::pseudorigid {

/// The error norm of a run of mechanism m on sys (built on m; it must outlive the stepper):
/// - m.simulation.error_norm "body": sys's body norm (MechanismSystem::error_norm);
/// - "state", mass_scaled: the weighted RMS with atol scaled per state, so that atol means
///   metres for positions and metres per second for momenta: a mass's momenta at its mass,
///   a dummy mass's at a quarter of its body's mass (its error would otherwise resolve the
///   stiff, energy-free vibration of the tiny mass), a rigid body's quaternion at 1 and its
///   angular momentum at its smallest principal moment. For 1 kg masses this is the plain
///   norm (docs/pseudorigid.md, "error norm");
/// - "state", not mass_scaled: the plain weighted RMS (the robot's runs today).
ode::ErrorNorm solver_norm(const Mechanism& m, const MechanismSystem& sys, bool mass_scaled);

}  // namespace pronk::pseudorigid
