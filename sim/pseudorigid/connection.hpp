// Connections between two nodes (Ridgely 2001, §4.2.3). One connection may combine
// several laws on the same pair (a compound connection):
//   spring   F = -k (l - l0) e            (l0 = 0: F = -k d, no direction needed)
//   damper   F = -b (e . v) e             (along the connection)
//   friction F = -c v                     (linear, along the relative velocity)
//   drag     F = -q |v| v                 (quadratic)
//   actuator a spring-damper whose force is clamped to +-force_limit; its work
//            counts as actuator work, not as stored energy (a PD length controller)
// with d = x_a - x_b, l = |d|, e = d / l, v = v_a - v_b; F acts on a, -F on b.
// Zero-length rule: when l < epsilon the direction is undefined, the terms
// that need it contribute nothing and the event is counted.
#pragma once

#include <string>

#include <Eigen/Core>

#include "sim/pseudorigid/node.hpp"

namespace pronk::pseudorigid {

/// Energy class of a connection's spring (energy accounting).
enum class ConnectionClass { kInternal, kLeg, kOther, kActuator };

struct Connection {
  std::string name;
  NodeRef a, b;
  ConnectionClass kind = ConnectionClass::kOther;
  double stiffness = 0.0;    ///< k [N/m]
  double rest_length = 0.0;  ///< l0 [m] (a run may change it: MechanismInputs, inputs.hpp)
  double damping = 0.0;      ///< b, along the connection [N s/m]
  double friction = 0.0;     ///< c, linear in the relative velocity [N s/m]
  double drag = 0.0;         ///< q, quadratic [N s^2/m^2]
  double force_limit = 0.0;  ///< actuator only: |F| clamp [N]; 0 = none
};

/// Force on node a and its derivatives with respect to d and v.
struct ConnectionForce {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();        ///< on a [N]
  Eigen::Vector3d dissipative = Eigen::Vector3d::Zero();  ///< damper + friction + drag part [N]
  Eigen::Matrix3d d_dx = Eigen::Matrix3d::Zero();         ///< dF/dd [N/m]
  Eigen::Matrix3d d_dv = Eigen::Matrix3d::Zero();         ///< dF/dv [N s/m]
  bool zero_length = false;                               ///< the zero-length rule dropped a term
  double length = 0.0;                                    ///< |d| [m]
};

/// Evaluates the connection law with rest length l0 = rest_length [m] (the run's, in place of
/// c.rest_length) at relative position d [m] and velocity v [m/s]; without `derivatives` d_dx
/// and d_dv are left unset (not exact; the RHS does not need them).
ConnectionForce connection_force(const Connection& c, double rest_length, const Eigen::Vector3d& d,
                                 const Eigen::Vector3d& v, double epsilon, bool derivatives = true);

/// Stored energy of the spring with rest length rest_length [m] [J] (0 for actuators).
double connection_energy(const Connection& c, double rest_length, const Eigen::Vector3d& d);
/// The same at a known length |d| [m] (bit for bit: connection_energy is this at d.norm()).
double connection_energy_at(const Connection& c, double rest_length, double length);

}  // namespace pronk::pseudorigid
