// Energy accounting (Ridgely 2001, §3.5.2): stored energies by class at one state, and
// the rates (dissipated power, actuator power) the simulator integrates with
// Gauss-Legendre quadrature on each step's dense output. The balance
// total + dissipated - actuator_work is constant for an exact solution.
#pragma once

namespace pronk::pseudorigid {

struct Energies {
  double kinetic = 0.0;        ///< sum p^2 / 2m [J]
  double gravitational = 0.0;  ///< -sum m g . x [J]
  double applied = 0.0;        ///< potential of constant world forces, -F . x [J]
  double internal = 0.0;       ///< internal (body) springs [J]
  double leg = 0.0;            ///< leg springs [J]
  double other = 0.0;          ///< other springs [J]
  double contact = 0.0;        ///< surface springs [J]
  double total() const {
    return kinetic + gravitational + applied + internal + leg + other + contact;
  }
};

struct PowerFlows {
  double dissipated = 0.0;  ///< power lost in dampers, friction, drag [W] (>= 0)
  double actuator = 0.0;    ///< power delivered by body forces and actuators [W]
};

}  // namespace pronk::pseudorigid
