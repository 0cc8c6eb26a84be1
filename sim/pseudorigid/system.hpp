// The mechanism as an ODE system: right-hand side, analytic sparse Jacobian
// (3x3 blocks per connection, surface and force, including the rotation
// dependence of ghost-point transfer and body-relative directions), the
// optional body-level error norm, energies and monitors. One object per run
// (it holds scratch space, memos and a counter); the Mechanism it refers to is const, and
// what the run changes as it goes (rest lengths, surfaces) it reads from the run's
// MechanismInputs (inputs.hpp). The implementation, one concern per file: system.cpp (the
// skeleton: construction, kinematics, the right-hand side), system_connections.cpp (the
// connections' forces, the transfer of node forces), system_surfaces.cpp (surfaces with their
// Jacobian blocks), system_jacobian.cpp (the Jacobian's assembly and check),
// system_dissipation.cpp (the dissipation split of method verlet), system_observe.cpp (the error
// norm, energies, power, monitors).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "sim/ode/mechanical_system.hpp"
#include "sim/pseudorigid/attitude.hpp"
#include "sim/pseudorigid/energy.hpp"
#include "sim/pseudorigid/inputs.hpp"
#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

/// One held (surface, node) pair as observe() reads it: known (its force does not depend on
/// velocities, so the conservative evaluation's is the whole force), whether it touches
/// (geometric: known from the positions alone), penetration [m], |P r|^2 [m^2] (the contact
/// energy's) and |F| [N].
struct PairSeen {
  bool known = false;      ///< all fields valid
  bool geometric = false;  ///< touching valid
  bool touching = false;
  double penetration = 0.0, projected2 = 0.0, force = 0.0;
};

/// Accuracy monitors of one state.
struct StateMonitors {
  double max_strain = 0.0;       ///< largest |l - l0| / l0 over internal springs
  double max_penetration = 0.0;  ///< deepest plane penetration or constraint violation [m]
};

class MechanismSystem final : public ode::MechanicalSystem {
 public:
  /// With inputs of its own, as the Mechanism has them (a run that changes none).
  explicit MechanismSystem(const Mechanism& m);
  /// Reads the run's `inputs` (sized to m; they outlive the system) at every evaluation.
  MechanismSystem(const Mechanism& m, const MechanismInputs& inputs);

  int dimension() const override { return m_.dimension(); }
  void rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  bool has_jacobian() const override { return true; }
  void jacobian(double t, const ode::Vec& y, Eigen::SparseMatrix<double>& J) const override;
  bool autonomous() const override { return true; }  // time windows are handled by segment_time
  /// The body-level error norm (SimulationOptions::error_norm "body"; solver_norm.hpp hands
  /// it to the adaptive steppers).
  double error_norm(const ode::Vec& err, const ode::Vec& y0, const ode::Vec& y1, double rtol,
                    double atol) const;

  /// y = (x_j, p_j) per mass: dx/dt = p/m depends on the momenta only (method verlet).
  void momentum_mask(ode::Vec& mask) const override;
  void position_rate(const ode::Vec& y, ode::Vec& dydt) const override;
  /// sum |p_j|^2 / 2 m_j [J] over the momentum entries of y.
  double kinetic_energy(const ode::Vec& y) const override;
  int momentum_block() const override { return 3; }

  /// Dissipation split (method verlet): the dampers, friction and drag of connections (not
  /// actuators) and surfaces leave the kicks. Offered unless a dissipative element acts on a
  /// ghost point under the min_norm transfer (its impulse has no scalar effective mass).
  bool has_dissipation_split() const override { return dissipation_split_; }
  /// rhs() without those forces (friction's normal force then has no damping term either).
  void conservative_rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  /// Each dissipative element in model order as an implicit (backward Euler) impulse over
  /// h [s] on its two nodes' momenta at fixed positions: linear dampers and friction in
  /// closed form, drag and regularised Coulomb friction by a monotone scalar solve. Every
  /// update conserves momentum and removes energy whatever h. Returns the energy to book
  /// as dissipated [J]: -sum_j dP_j . (v_ref_j + dP_j / 2 m_j) over the masses' momentum
  /// changes dP_j, with v_ref the velocities of y_ref (see MechanicalSystem::dissipate).
  double dissipate(double t, double h, const ode::Vec& y_ref, ode::Vec& y) const override;
  /// Grounded one-sided planes: a node that entered or left the contact during the step
  /// gets an impulse along the normal that makes the step's kinetic energy change match the
  /// exact potential change of its contact spring, 1/2 k (min(0, z1)^2 - min(0, z0)^2) for
  /// gaps z0, z1, instead of the trapezoidal work of the Verlet kicks (the discrete-gradient
  /// contact force of energy-conserving contact schemes). Of the two roots the smaller
  /// impulse; when the node's normal motion cannot supply the energy, it stops it.
  void correct_step(const ode::Vec& y0, ode::Vec& y1) const override;
  /// A rigid body's rotation (rigid_body.hpp): the drift of method verlet turns it by the
  /// free rigid body's splitting flow; the masses drift by h p / m as usual.
  bool has_drift() const override { return any_rigid_; }
  void drift(double h, ode::Vec& y) const override;
  /// True when the mechanism has a rigid body (Body::rigid).
  bool has_rigid_body() const { return any_rigid_; }
  /// Index of body b's rotation states in y (-1: a four-mass body).
  int rotation_state(int b) const { return rot_[static_cast<size_t>(b)]; }
  /// Adds a force F [N] at node n to the momentum rates of dydt (a ghost point of a rigid body:
  /// on its CoM mass plus the torque r x F on its angular momentum; of a four-mass body: by
  /// the barycentric weights).
  void add_node_force(const NodeRef& n, const Eigen::Vector3d& f, const ode::Vec& y,
                      ode::Vec& dydt) const;
  /// True when actuators or applied forces do work (power().actuator is not always zero).
  bool has_actuator_work() const { return has_actuator_work_; }

  /// Time-windowed forces (body forces, impulse actuators) are on or off for a
  /// whole integration segment: the simulator stops at every switch time and
  /// calls this with a time inside the next segment [s].
  void set_segment_time(double t) { segment_time_ = t; }

  /// Body frames (attitude, CoM) at y; valid until the next call.
  const std::vector<BodyFrame>& frames(const ode::Vec& y) const;
  // (inline: hot; a rigid body's ghost point as point_position and point_velocity give it)
  Eigen::Vector3d node_position(const NodeRef& n, const ode::Vec& y) const {
    if (n.kind == NodeRef::Kind::kMass) return y.segment<3>(6 * n.index);
    if (rigid_node(n)) {
      const GhostPoint& g = m_.ghost_points[n.index];
      return y.segment<3>(6 * m_.bodies[g.body].first_mass) +
             rigid_pose(g.body, y).rotation * g.local;
    }
    return point_position(n, y);
  }
  Eigen::Vector3d node_velocity(const NodeRef& n, const ode::Vec& y) const {
    if (n.kind == NodeRef::Kind::kMass) return y.segment<3>(6 * n.index + 3) * inv_mass_[n.index];
    if (rigid_node(n)) {
      const GhostPoint& g = m_.ghost_points[n.index];
      const int f = m_.bodies[g.body].first_mass;
      const RigidState& k = rigid_state(g.body, y);
      return y.segment<3>(6 * f + 3) * inv_mass_[f] + k.omega.cross(k.rotation * g.local);
    }
    return point_velocity(n, y);
  }
  Eigen::Vector3d reference_position(int i, const ode::Vec& y) const;
  /// World-frame angular velocity of body b [rad/s] (least squares).
  Eigen::Vector3d body_omega(int b, const ode::Vec& y) const;

  Energies energies(const ode::Vec& y) const;
  PowerFlows power(const ode::Vec& y) const;
  /// False when nothing dissipates or does work: power() is then zero everywhere.
  bool has_power_flows() const { return has_power_flows_; }
  StateMonitors monitors(const ode::Vec& y) const;
  /// Largest contact force magnitude of each surface at y [N].
  std::vector<double> surface_forces(const ode::Vec& y) const;
  /// A grounded plane's contact on node n at y: its normal force N >= 0 [N] (spring and
  /// damper) and its friction force [N] (world); both zero off contact.
  struct Contact {
    double normal = 0.0;
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();
  };
  Contact contact(int surface, const NodeRef& n, const ode::Vec& y) const;
  /// energies(), monitors() and surface_forces() in one pass (each surface evaluated once);
  /// null outputs are skipped; surface_max (sized to the surfaces) is raised to the forces
  /// at y, not overwritten.
  void observe(const ode::Vec& y, Energies* energies, StateMonitors* monitors,
               std::vector<double>* surface_max) const;

  /// RHS evaluations in which the zero-length rule fired.
  long zero_length_triggers() const { return zero_length_; }
  /// observe() calls that read the last conservative evaluation (GeometryMemo) instead of
  /// computing the positions' part again.
  long memo_hits() const { return memo_hits_; }
  /// The run-time inputs it reads.
  const MechanismInputs& inputs() const { return *in_; }
  /// The inverse effective mass of node n at y for an impulse along unit d [1/kg]:
  /// inverse_mass(n) (a ghost point of four masses: sum w_i^2 / m_i by its barycentric
  /// weights) unless n is a ghost point of a rigid body, 1/M + (r x d) . I_w^-1 (r x d) there.
  double inverse_mass_along(const NodeRef& n, const ode::Vec& y, const Eigen::Vector3d& d) const;
  /// Applies impulse j [N s] at node n to the momenta of y (a ghost point of four masses: by
  /// its barycentric weights; of a rigid body: its momentum and angular momentum).
  void add_impulse(const NodeRef& n, const Eigen::Vector3d& j, ode::Vec& y) const;

 private:
  /// The constructors': the inputs held (own) or, when null, the run's (inputs).
  MechanismSystem(const Mechanism& m, std::unique_ptr<const MechanismInputs> own,
                  const MechanismInputs* inputs);
  /// The forces an evaluation includes: all of them (rhs), or all but the dissipative elements
  /// (conservative_rhs: the velocities of dampers, friction and drag count as zero).
  enum class ForceSet { kAll, kConservative };
  /// rhs() (kAll) and conservative_rhs() (kConservative).
  void evaluate(ForceSet set, const ode::Vec& y, ode::Vec& dydt) const;
  /// evaluate()'s connection forces into force_ (with `memo`, each length into memo_); counts
  /// an evaluation in which the zero-length rule fired (zero_length_).
  void add_connection_forces(ForceSet set, const ode::Vec& y, bool memo) const;
  /// evaluate()'s surface forces of every held (surface, node) pair into force_ and torque_
  /// (with `memo`, what observe() reads of each pair into memo_.pairs).
  void add_surface_forces(ForceSet set, const ode::Vec& y, bool memo) const;
  /// The nodes surface si holds now: its own, or none (SurfaceInputs::holds).
  const std::vector<NodeRef>& held_nodes(size_t si) const {
    return in_->surfaces[si].holds ? m_.surfaces[si].nodes : no_nodes_;
  }
  /// A rigid body's rotation and angular velocity at its last 7 rotation states (rigid_state).
  /// node_position and node_velocity of what they do not compute inline: a ghost point of a
  /// four-mass body (barycentric) or an anchor.
  Eigen::Vector3d point_position(const NodeRef& n, const ode::Vec& y) const;
  Eigen::Vector3d point_velocity(const NodeRef& n, const ode::Vec& y) const;
  struct RigidState {
    /// (NaN: matches no state, so the first call computes.)
    Eigen::Matrix<double, 7, 1> key =
        Eigen::Matrix<double, 7, 1>::Constant(std::numeric_limits<double>::quiet_NaN());
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Identity();  ///< world R I^-1 R^T
    Eigen::Vector3d omega = Eigen::Vector3d::Zero();                ///< world [rad/s]
  };
  struct Transfer {
    int mass;
    Eigen::Matrix3d t;  ///< force on the mass = t * force on the node
  };
  void update_frames(const ode::Vec& y, bool derivatives) const;
  bool active(double t_start, double t_end) const {
    return segment_time_ >= t_start && segment_time_ < t_end;
  }
  /// Adds F at node n into force_ (distributed for ghost points).
  void apply(const NodeRef& n, const Eigen::Vector3d& f) const;
  int transfers(const NodeRef& n, std::array<Transfer, 4>& out) const;
  /// dissipate(): inverse effective mass of node n for an impulse [1/kg] (barycentric
  /// ghost transfer: sum w_i^2 / m_i; anchors 0), and the impulse J [N s] applied to it.
  double inverse_mass(const NodeRef& n) const;
  /// n is a ghost point of a rigid body.
  bool rigid_node(const NodeRef& n) const {
    return n.kind == NodeRef::Kind::kGhost && rot_[m_.ghost_points[n.index].body] >= 0;
  }
  /// Body-attached surface si on a rigid body: the force on node n, its reaction at the
  /// surface's ghost point and the torque of the turning direction (attached_surface_forces)
  /// into force_ and torque_.
  /// With `seen`, what observe() needs of the pair into it (GeometryMemo).
  void rigid_surface_forces(size_t si, const NodeRef& n, const ode::Vec& y, ForceSet set,
                            PairSeen* seen = nullptr) const;
  /// Rigid body b's rotation and angular velocity at y, memoised (a pure function of its 7
  /// rotation states, compared exactly: one RHS reads them for every ghost point).
  const RigidState& rigid_state(int b, const ode::Vec& y) const {
    const RigidState& k = rigid_pose(b, y);  // (inline: hot; the memo's miss out of line)
    const int r = rot_[static_cast<size_t>(b)];
    if (y[r + 4] == k.key[4] && y[r + 5] == k.key[5] && y[r + 6] == k.key[6]) return k;
    return update_rigid_omega(b, y);
  }
  const RigidState& update_rigid_omega(int b, const ode::Vec& y) const;
  /// Rigid body b's world inverse inertia in the attitude of the last frames_ (from the
  /// rigid_pose memo when that is at the same rotation).
  Eigen::Matrix3d frame_inverse_inertia(size_t b) const;
  /// memo_ holds for y: computed at y's positions (masses, quaternions) and the current
  /// surface inputs.
  bool memo_holds(const ode::Vec& y) const;
  /// A conservative evaluation at y starts the memo over.
  void begin_memo(const ode::Vec& y) const;
  /// rigid_state without the angular velocity (rotation and world inverse inertia, memoised
  /// on the quaternion alone; omega is not current in the result).
  const RigidState& rigid_pose(int b, const ode::Vec& y) const {
    const RigidState& k = rigid_[static_cast<size_t>(b)];  // (inline: hot; the miss out of line)
    const int r = rot_[static_cast<size_t>(b)];
    if (y[r] == k.key[0] && y[r + 1] == k.key[1] && y[r + 2] == k.key[2] && y[r + 3] == k.key[3])
      return k;
    return update_rigid_pose(b, y);
  }
  const RigidState& update_rigid_pose(int b, const ode::Vec& y) const;
  /// dissipate()'s implicit velocity updates of the dampers, friction and drag of the
  /// connections, then of the surfaces' dampers and friction (momenta of y only).
  void dissipate_connections(double h, ode::Vec& y) const;
  void dissipate_surfaces(double h, ode::Vec& y) const;
  /// dissipate()'s booking: -sum dP . (v_ref + dP / 2m) over the momentum changes y - y_before.
  double booked_dissipation(const ode::Vec& y_ref, const ode::Vec& y_before,
                            const ode::Vec& y) const;
  /// rhs(): the rigid bodies' rotation rates from torque_.
  void rigid_rates(const ode::Vec& y, ode::Vec& dydt) const;
  void add_block(int row, int col, const Eigen::Matrix3d& b) const;
  void jac_force(const NodeRef& target, const NodeRef& source, const Eigen::Matrix3d& kx,
                 const Eigen::Matrix3d& kv) const;
  void jac_rotation(const NodeRef& target, int body, const Eigen::Matrix3d& d) const;
  void jac_transfer(const NodeRef& target, const Eigen::Vector3d& f) const;
  /// A surface's force on node n with its geometry (type, direction, r) and velocity.
  struct SurfaceEval {
    bool active = false;
    SurfaceType type = SurfaceType::kPlane;  ///< what the surface constrains (project())
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
    Eigen::Vector3d dir = Eigen::Vector3d::Zero();
    double penetration = 0.0;
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();  ///< friction part of force [N]
    double normal = 0.0;  ///< normal force N >= 0 the friction scales with [N]
    /// u's constrained components P u: along dir (plane), across it (line), all (point).
    Eigen::Vector3d project(const Eigen::Vector3d& u) const { return project_onto(type, dir, u); }
  };
  SurfaceEval eval_surface(size_t si, const NodeRef& n, const ode::Vec& y, ForceSet set) const;
  /// A touching pair's evaluation as observe() reads it (all fields known).
  static PairSeen seen_of(const SurfaceEval& e);
  /// The geometry part of eval_surface (dir, r, type, penetration into e); false when a
  /// one-sided plane is not touched. Needs frames_ current for a body-attached surface.
  bool surface_gap(size_t si, const NodeRef& n, const ode::Vec& y, SurfaceEval& e) const;
  /// Forces of body-attached surface si on node n as the exact gradient of its
  /// potential U = 1/2 k |P(R) (x_n - p)|^2 (p = sum w_i x_i the surface's ghost
  /// point, P turning with the Kabsch rotation R): F on n, -F on the body masses
  /// by the barycentric weights w_i, and the direction's rotation torque
  /// tau = -dU/dtheta distributed by the Kabsch derivative, f_k = Omega_k^T R^T tau;
  /// damping -b P (v_n - v_p) goes the same way (its power is exactly the
  /// dissipated power). Computed from y alone. Adds (mass, force [N]) pairs to out.
  /// `known_frame`: the body's frame at y when the caller has it (else fitted here).
  /// `known_omega`: attitude_derivative(*known_frame) when the caller has it.
  void attached_surface_forces(size_t si, const NodeRef& n, const ode::Vec& y, ForceSet set,
                               std::vector<std::pair<int, Eigen::Vector3d>>& out,
                               const BodyFrame* known_frame = nullptr,
                               const std::array<Eigen::Matrix3d, 4>* known_omega = nullptr) const;
  /// jacobian(): the blocks of grounded surface si's touching nodes (spring, damper, friction).
  void grounded_surface_jacobian(size_t si, const ode::Vec& y) const;
  /// Jacobian blocks of the attached_surface_forces of every active node on
  /// surfaces attached to body b, by forward differences.
  void attached_surfaces_jacobian(int b, const ode::Vec& y) const;

  /// fit_attitude of body b's masses at y, memoised: a fit is a pure function of the
  /// four positions, and one RHS of a robot asks for the same frame several times
  /// (feedback, leg directions, angular velocity). Valid until the next call for b.
  const BodyFrame& fitted_frame(int b, const ode::Vec& y) const;

  const Mechanism& m_;
  std::unique_ptr<const MechanismInputs> own_inputs_;  ///< the one-argument constructor's
  const MechanismInputs* in_;            ///< the inputs read: own_inputs_ or the run's
  const std::vector<NodeRef> no_nodes_;  ///< held_nodes() of a surface that holds none
  double segment_time_ = 0.0;
  std::vector<double> inv_mass_;
  /// The RHS (and energies, power, monitors) need body frames: body-relative forces
  /// or actuators, body-attached surfaces, or the rotation-dependent min-norm
  /// ghost transfer.
  bool rhs_needs_frames_ = true;
  /// Anything dissipates or does work (dampers, friction, drag, actuators, surface
  /// dampers, body forces); otherwise power() is zero without evaluation.
  bool has_power_flows_ = false;
  bool has_actuator_work_ = false;
  bool has_attached_surfaces_ = false;
  bool dissipation_split_ = true;
  std::vector<int> rot_;  ///< per body: its rotation states (rigid), else -1
  bool any_rigid_ = false;

  // The mutable members, per object (one run), never shared.
  // Pure caches, keyed exactly on the states they are a function of: a hit returns what a
  // miss computes, bit for bit. The positions of each body's masses at its last fit and that
  // fit (fitted_frame); each rigid body's rotation, world inverse inertia and angular
  // velocity at its last quaternion and angular momentum (rigid_pose, rigid_state).
  mutable std::vector<std::array<Eigen::Vector3d, 4>> fit_x_;
  mutable std::vector<BodyFrame> fit_frame_;
  mutable std::vector<bool> fit_valid_;
  mutable std::vector<RigidState> rigid_;
  // What observe() reads of the last conservative evaluation (split Verlet's one RHS per
  // step, whose positions the step keeps): each connection's length, and per held
  // (surface, node) pair whose force does not depend on velocities (no damper, no friction)
  // whether it touches, its penetration, |P r|^2 and |F|; with the state and the surfaces'
  // inputs they hold for (memo_holds: the positions and inputs compared exactly).
  struct GeometryMemo {
    ode::Vec y;
    std::vector<SurfaceInputs> surfaces;
    std::vector<double> length;
    std::vector<PairSeen> pairs;
    bool valid = false;
  };
  mutable GeometryMemo memo_;
  // Scratch, written before it is read within one call: the body frames at the y of the
  // last update_frames, the forces and torques an evaluation accumulates, the Jacobian's
  // triplets, one attached surface's forces, dissipate()'s momenta before its updates. One
  // reader keeps state across calls: kinetic_energy() takes a rigid body's attitude from the
  // last frames_ (its argument is a force vector with no attitude in it; see there).
  mutable std::vector<BodyFrame> frames_;
  mutable std::vector<std::array<Eigen::Matrix3d, 4>> dframes_;
  mutable ode::Vec force_;
  mutable std::vector<Eigen::Vector3d> torque_;  ///< rhs(): torque on each rigid body [N m]
  mutable std::vector<Eigen::Triplet<double>> triplets_;
  mutable std::vector<std::pair<int, Eigen::Vector3d>> attached_;
  mutable ode::Vec dissipate_before_;
  // A run statistic, counted by every RHS evaluation and read by nothing that computes:
  // zero_length_triggers().
  mutable long zero_length_ = 0;
  mutable long memo_hits_ = 0;  ///< memo_hits()
};

/// Compares the analytic Jacobian at (t, y) with central differences of the
/// RHS; returns the largest |J_analytic - J_fd| relative to max(1, |J|_max).
double jacobian_check(const MechanismSystem& sys, double t, const ode::Vec& y,
                      int* worst_row = nullptr, int* worst_col = nullptr);

}  // namespace pronk::pseudorigid
