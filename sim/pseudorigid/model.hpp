// The pseudo-rigid mechanism model (Ridgely 2001, ch. 3-4; docs/pseudorigid.md): point masses with
// position and momentum states, bodies made of four equal masses held by six
// stiff internal springs, reference and ghost points that move with a body,
// connections, constraint surfaces, forces and actuators. A Mechanism is built
// once (by the JSON loader or in code with the helpers of builder.hpp), then it
// is const and shareable: every run keeps its own state (system.hpp,
// simulator.hpp).
//
// State layout: mass j owns y[6j .. 6j+2] = position [m] and
// y[6j+3 .. 6j+5] = momentum [N s]. After all masses, each rigid body (Body::rigid) owns
// 7 states: its attitude quaternion (w, x, y, z) and world angular momentum [N m s]. Ghost
// points, reference points, anchors and grounded surfaces contribute no states.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/body.hpp"
#include "sim/pseudorigid/connection.hpp"
#include "sim/pseudorigid/force.hpp"
#include "sim/pseudorigid/ghost_point.hpp"
#include "sim/pseudorigid/mass.hpp"
#include "sim/pseudorigid/node.hpp"
#include "sim/pseudorigid/surface.hpp"

namespace pronk::pseudorigid {

/// Which error norm the adaptive solvers use.
enum class ErrorNorm {
  kState,  ///< per-state RMS norm over every position and momentum
  kBody,   ///< body-level: CoM position/velocity, attitude, angular velocity of each
           ///< body, and the states of free masses; internal vibration is not measured
};

/// How a force applied at a ghost point is distributed over the body's four masses.
enum class GhostTransfer {
  /// f_i = w_i F with the barycentric weights w_i that also define the ghost point's
  /// position p = sum w_i x_i: net force and moment about the centroid are exact for
  /// any deformation, and the forces are the gradient of any potential of p, so the
  /// energy balance holds (default).
  kBarycentric,
  /// The seed's minimum-norm solution F_i = R G_i R^T F. Same net force and moment
  /// for the rigid configuration, but not consistent with the barycentric position:
  /// the self-equilibrated difference does work through the internal deformation and
  /// the energy balance drifts (measured: 3.5e-2 of the energy scale in 3 s of the
  /// four-leg drop with internal k = 1e5 N/m; barycentric: 3.5e-6).
  kMinNorm,
};

/// How a run is integrated and monitored.
struct SimulationOptions {
  double t_end = 1.0;             ///< simulated time [s]
  double output_interval = 1e-2;  ///< sampling of the trajectory outputs [s]
  ode::SolverOptions solver = default_solver();
  ErrorNorm error_norm = ErrorNorm::kState;
  bool euler_313 = false;  ///< attitude output as 3-1-3 (else 1-2-3) Euler angles
  double energy_blowup_factor =
      10;  ///< energy drift above this times the energy scale = divergence
  GhostTransfer ghost_transfer = GhostTransfer::kBarycentric;
  bool check_jacobian = false;  ///< compare the analytic Jacobian with central differences at t=0
  double zero_length_epsilon = 1e-12;  ///< connection length below which no direction exists [m]
  /// Method verlet: 0 (default) steps at h_fixed. A positive value bounds Verlet's bounded
  /// energy term h^2 |F|^2 / 8m (the sampled energy's departure from the conserved modified
  /// energy, large inside impacts) to energy_tol x the run's energy scale at every step:
  /// h_fixed becomes the grid step, sub-stepped where needed
  /// (ode::SolverOptions::verlet_energy_budget). The term is the balance's whole departure
  /// for quadratic potentials only: springs that turn within a step add Verlet's own O(h^2)
  /// error (the run's energy_drift reports the total). Ignored by the other methods.
  double energy_tol = 0.0;
  /// Accuracy budgets: a run whose realised maximum internal strain (|l - l0| / l0) or
  /// penetration / constraint violation [m] exceeds them completes with a warning
  /// (RunSummary::warnings), so a user sees that the pseudo-rigid approximation did not hold.
  /// The same numbers drive "internal_stiffness": "auto" / "contact_stiffness": "auto".
  double strain_budget = 1e-4;
  double penetration_budget = 1e-4;  ///< [m]

  static ode::SolverOptions default_solver() {
    ode::SolverOptions s;
    s.method = ode::Method::kRodas4;
    s.rtol = 1e-6;
    s.atol = 1e-8;
    s.h_max = 0.1;
    return s;
  }
  /// Checks every field; on failure writes "field: value: rule" into *error.
  bool validate(std::string* error) const;
};

/// The immutable description of a mechanism.
struct Mechanism {
  std::string name = "mechanism";
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  ///< acceleration of gravity on every mass [m/s^2]
  std::vector<Mass> masses;
  std::vector<Body> bodies;
  std::vector<Anchor> anchors;
  std::vector<GhostPoint> ghost_points;
  std::vector<ReferencePoint> reference_points;
  std::vector<Connection> connections;
  std::vector<Surface> surfaces;
  std::vector<WorldForce> world_forces;
  std::vector<BodyForce> body_forces;
  std::vector<ImpulseActuator> impulse_actuators;
  SimulationOptions simulation;

  /// 6 per mass, then 7 per rigid body (quaternion, angular momentum; rigid_body.hpp).
  int dimension() const { return 6 * static_cast<int>(masses.size()) + 7 * rigid_bodies(); }
  int rigid_bodies() const;
  /// Index in y of rigid body b's quaternion (its angular momentum follows at +4); -1 for
  /// a four-mass body.
  int rotation_state(int b) const;
  double total_mass() const;
  /// The initial state vector.
  Eigen::VectorXd initial_state() const;
  /// Structural checks (indices in range, positive masses, ...); message on failure.
  bool validate(std::string* error) const;
  /// Name of a node for output headers.
  std::string node_name(const NodeRef& n) const;
};

}  // namespace pronk::pseudorigid
