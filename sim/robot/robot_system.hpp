// The robot as an ODE system: the mechanism's own forces (MechanismSystem: body,
// leg springs and dampers, slides, ground contact with its regularised Coulomb foot
// friction F_t = -mu N v_t / sqrt(|v_t|^2 + v_s^2)) plus the run-time inputs a
// controller drives: leg actuator forces (along each leg, on the hip and, for spring
// legs, the opposite force on the foot; along the current foot -> hip line while the
// leg's hip is free) and the stance attitude feedback through them. The Jacobian is
// the mechanism's analytic one plus central differences of the actuator forces over
// the states they read. For the symplectic stepper the mechanism's structure is
// forwarded: its dissipation split (dampers and friction as implicit velocity updates),
// kinetic-energy metric and momentum blocks; the actuator forces stay in the kicks.
#pragma once

#include <array>
#include <vector>

#include "sim/pseudorigid/solver_norm.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"

namespace pronk::robot {

class RobotSystem final : public ode::MechanicalSystem {
 public:
  /// The mechanism is model.mechanism; `inputs` are the run's (hip placement and the foot
  /// switches change the leg rest lengths and slides there as the run goes).
  RobotSystem(const RobotModel& model, const pseudorigid::MechanismInputs& inputs,
              const scene::PseudoRigid& settings);

  /// The mechanism's states, then (quasi-static feet) two per leg (foot_state()).
  int dimension() const override { return mech_dim_ + qs_states_; }
  /// The mechanism's initial state, the feet's states zero (quasi-static feet start in the air
  /// at their rest length).
  ode::Vec initial_state() const;
  void rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  bool has_jacobian() const override { return true; }
  void jacobian(double t, const ode::Vec& y, Eigen::SparseMatrix<double>& J) const override;
  bool autonomous() const override { return true; }
  void momentum_mask(ode::Vec& mask) const override;
  void position_rate(const ode::Vec& y, ode::Vec& dydt) const override;
  double kinetic_energy(const ode::Vec& y) const override { return sys_.kinetic_energy(y); }
  int momentum_block() const override { return sys_.momentum_block(); }
  /// The mechanism's dissipation split. The actuator forces (the stance feedback's kd
  /// part included) stay in the kicks: they act on the body's rotation, kd / I ~ 1e2 1/s,
  /// far from stiff at the steps the springs allow.
  bool has_dissipation_split() const override { return sys_.has_dissipation_split(); }
  bool has_drift() const override { return sys_.has_drift(); }
  void drift(double h, ode::Vec& y) const override { sys_.drift(h, y); }
  void conservative_rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  double dissipate(double t, double h, const ode::Vec& y_ref, ode::Vec& y) const override;
  /// Quasi-static feet: each landed foot's ground position by the creep law, each foot in
  /// the air relaxing to its rest length, backward Euler over h at fixed body
  /// (robot_system_feet.cpp).
  bool has_relaxation() const override { return qs_states_ > 0; }
  double relax(double h, ode::Vec& y, bool* forces_moved) const override;
  void correct_step(const ode::Vec& y0, ode::Vec& y1) const override { sys_.correct_step(y0, y1); }

  /// Signed actuator force of each leg [N] (positive pushes the body away from
  /// the foot) along the unit body-frame push direction `push` (= -leg direction).
  void set_actuators(const std::vector<double>& force, const std::vector<Eigen::Vector3d>& push) {
    force_ = force;
    push_ = push;
    drop_memos();
  }
  const std::vector<double>& actuator_forces() const { return force_; }
  /// The tilt the stance attitude feedback holds: roll and pitch [rad] (small angles, about
  /// body x and y; 0 by default: level). The attitude integral action sets it per stride.
  void set_stance_tilt(const Eigen::Vector2d& tilt) {
    stance_tilt_ = tilt;
    drop_memos();
  }
  /// Each leg's total actuator force at y [N]: the set force plus, for a grounded
  /// leg, the stance attitude feedback (settings stance_kp, stance_kd).
  std::vector<double> actuator_forces(const ode::Vec& y) const;
  /// Frees leg i's hip (stance with rotating hips: the slide becomes a slot) or
  /// locks it. A free leg's actuator pushes along the current foot -> hip line (like
  /// the leg spring), not along `push`.
  void set_free(size_t i, bool free) {
    free_[i] = free;
    drop_memos();
  }
  bool free(size_t i) const { return free_[i]; }
  /// Unit world direction of leg i's actuator push on the body (foot -> hip for a
  /// free leg, R push otherwise).
  Eigen::Vector3d push_world(size_t i, const ode::Vec& y) const;
  /// push_world with the body's rotation R at y already known.
  Eigen::Vector3d push_world(size_t i, const ode::Vec& y, const Eigen::Matrix3d& R) const;

  const pseudorigid::MechanismSystem& mechanism() const { return sys_; }
  /// The stored energies at y: the mechanism's, and the quasi-static feet's leg springs (in
  /// `leg`), slots and ground springs (in `contact`).
  pseudorigid::Energies energies(const ode::Vec& y) const;

  // Quasi-static feet (RobotModel::quasi_static_feet; robot_system_feet.cpp). A landed foot
  // is pinned at its ground position (two integrated states: x, y [m]; its depth is the
  // ground spring's in series with the leg and the slot); a free hip turns in pitch (the slot,
  // a plane through the hip holding the leg and the body x axis), a locked hip holds the foot
  // on the leg's line (two planes; feet_step_bound.hpp's slot_normals). In the
  // air a foot sits on its leg's line (direction) at the rest length minus the leg's
  // shortening (its first state [m], relaxing as a massless foot between spring, damper and
  // actuator does), and transmits nothing.
  bool quasi_static() const { return qs_states_ > 0; }
  /// Index of leg i's two foot states in y.
  int foot_state(size_t i) const { return mech_dim_ + 2 * static_cast<int>(i); }
  /// Leg i's foot position at y [m] (a foot mass's position, or the quasi-static foot's).
  Eigen::Vector3d foot_position(size_t i, const ode::Vec& y) const;
  /// Quasi-static legs' run-time inputs: rest length [m], leg direction hip -> foot and slot
  /// normal (body frame, unit).
  std::vector<double>& foot_rest() {
    drop_memos();
    return rest_;
  }
  const std::vector<double>& foot_rest() const { return rest_; }
  std::vector<Eigen::Vector3d>& foot_direction() {
    drop_memos();
    return dir_;
  }
  const std::vector<Eigen::Vector3d>& foot_direction() const { return dir_; }
  /// Quasi-static foot i is on the ground (its hip is free, free(i), from its landing until
  /// RobotRun locks it after the foot has risen kFootLift, as a foot mass's is).
  bool pinned(size_t i) const { return !pinned_.empty() && pinned_[i]; }
  /// Quasi-static foot i lands at y: pinned where it is, its hip freed (the slot).
  void land_foot(size_t i, ode::Vec& y);
  /// Quasi-static foot i lifts off at y: its leg's direction and shortening as they are (its
  /// hip stays free).
  void lift_foot(size_t i, ode::Vec& y);
  /// Quasi-static foot i's event value (it switches falling through 0): landed, the ground's
  /// normal force on it [N] (lift-off); in the air, its height [m] above the ground, or at and
  /// below it land_force_ minus the normal force the ground would take were it landed [N] (it
  /// lands when it reaches the ground and the ground would press it).
  double foot_event(size_t i, const ode::Vec& y) const;
  /// The ground's reaction on quasi-static foot i at y (world; zero in the air) [N];
  /// `feedback`: evaluate the stance feedback at y first (else the last evaluation's).
  Eigen::Vector3d ground_reaction(size_t i, const ode::Vec& y, bool feedback = true) const;
  /// The energy in quasi-static leg i's springs at y [J].
  double foot_energy(size_t i, const ode::Vec& y) const;
  /// The adaptive steppers' error norm: the mechanism's body norm or the plain state norm
  /// (not mass-scaled, unlike a mechanism run's: pseudorigid::solver_norm).
  ode::ErrorNorm error_norm() const {
    return pseudorigid::solver_norm(model_.mechanism, sys_, /*mass_scaled=*/false);
  }
  /// 3 per mass, plus 3 (the torque) with a rigid body.
  int actuator_force_size() const;
  /// Index of the rigid body's rotation states in y; -1 for the four-mass body.
  int rotation_state() const { return rotation_; }
  /// Work rate of the leg actuators at y [W] (friction and dampers are the mechanism's).
  double actuator_power(const ode::Vec& y) const;
  /// The leg actuators' forces on the masses at y (3 per mass) [N] into f (sized
  /// actuator_force_size(); a rigid body's torque [N m] follows the masses'); false (f
  /// untouched) when none acts.
  bool actuator_mass_forces(const ode::Vec& y, ode::Vec& f) const { return extra_forces(y, f); }
  /// Friction force on each foot (world) [N]; zero vectors off the ground.
  std::vector<Eigen::Vector3d> friction_forces(const ode::Vec& y) const;
  /// Ground normal force on each foot [N] (0 in the air).
  std::vector<double> normal_forces(const ode::Vec& y) const;

 private:
  /// Writes the actuator forces into f (3 per mass); returns false when there are none.
  bool extra_forces(const ode::Vec& y, ode::Vec& f) const;
  /// Adds the actuator forces at y to the momentum rates of dydt.
  void add_extra(const ode::Vec& y, ode::Vec& dydt) const;
  /// Stance attitude feedback: fills fb_ with each leg's extra actuator force
  /// (zero for legs off the ground); false when it is off or no leg is grounded.
  /// (Quasi-static feet: memoised, stance_feedback computes.)
  bool feedback(const ode::Vec& y) const;
  bool stance_feedback(const ode::Vec& y) const;
  /// Quasi-static feet: a landed leg's geometry and spring forces at its foot's ground
  /// position s (the depth solved in series), its hip and com at y and slot normal n (world).
  struct Stance {
    Eigen::Vector3d foot, d;       ///< foot [m]; unit foot -> hip
    double l = 0.0, spring = 0.0;  ///< length [m]; spring force k (l0 - l) [N], + pushes
    Eigen::Vector3d slot = Eigen::Vector3d::Zero();  ///< slot springs' force sum k_s e n [N]
    double depth = 0.0;                              ///< ground spring compression [m]
    double energy = 0.0;                             ///< springs' energy [J]
  };
  /// A landed leg's slot normals (world, unit): one for a free hip (the plane of the leg and
  /// the body x axis), two for a locked hip (the leg's line).
  struct Slot {
    std::array<Eigen::Vector3d, 2> n;
    int count = 0;
  };
  Stance stance(size_t i, const Eigen::Vector2d& s, const Eigen::Vector3d& hip,
                const Slot& sl) const;
  /// stance() of pinned leg i at its own ground position in y, memoised for every pinned leg
  /// on the body's position and attitude and the feet's states (valid until the next call).
  const Stance& stance_at(size_t i, const ode::Vec& y) const;
  void drop_memos() const { fb_memo_ = st_memo_ = false; }
  /// Landed leg i's slot normals at y (world).
  Slot slot_world(size_t i, const ode::Vec& y) const;
  /// Body-frame slot normals (zero when absent: slot_normals) turned to the world by R.
  static Slot to_world(const std::array<Eigen::Vector3d, 2>& body, const Eigen::Matrix3d& R);
  /// Adds the landed quasi-static legs' springs and slots (and, with `damped`, their dampers)
  /// to the body's momentum rates; writes the feet's state rates (`rates`: the creep and
  /// relaxation; otherwise 0).
  void add_feet(const ode::Vec& y, bool damped, bool rates, ode::Vec& dydt) const;
  /// Leg i's actuator force as extra_forces applies it (after feedback(y)) [N].
  double applied_actuator(size_t i) const;
  /// A landed leg's ground reaction (world) [N] in stance st with actuator a [N] and hip
  /// velocity vh.
  Eigen::Vector3d reaction(const Stance& st, const Eigen::Vector3d& vh, double a) const;
  /// relax(): landed leg i's ground position after h [s] (backward Euler of the creep law
  /// as the minimum of the springs' energy plus the friction's dissipation potential);
  /// *released: the springs' energy it released [J].
  Eigen::Vector2d creep(size_t i, double h, const Eigen::Vector2d& s0, const Eigen::Vector3d& hip,
                        const Slot& sl, const Eigen::Vector3d& vh, double a,
                        double* released) const;
  /// (quasi-static feet) A force f [N] at leg i's hip on the body, into the momentum rates of
  /// dydt (rigid body: its CoM and angular momentum; four masses: by the hip's barycentric
  /// weights, the gradient of an energy of the hip's position).
  void load_hip(size_t i, const Eigen::Vector3d& f, const ode::Vec& y, ode::Vec& dydt) const;
  /// (quasi-static feet) A torque tau [N m] (world) on the body, into dydt (four masses:
  /// through the fitted attitude's derivative with respect to the masses, the gradient of an
  /// energy of the body's attitude).
  void load_torque(const Eigen::Vector3d& tau, const ode::Vec& y, ode::Vec& dydt) const;
  /// The kinetic energy change booked by the dissipation split for momenta moved from y0 to
  /// y, against the reference momenta of y_ref [J] (MechanismSystem::dissipate's booking:
  /// -dP . (v_ref + dP / 2M) per mass, and the rigid body's rotation's).
  double booked_body(const ode::Vec& y_ref, const ode::Vec& y0, const ode::Vec& y) const;
  /// (quasi-static feet) the position states the stances read: the rigid body's CoM and
  /// attitude (7); otherwise every mass's position (the four and any dummy hip masses).
  int body_key_size() const { return rotation_ >= 0 ? 7 : 3 * static_cast<int>(inv_mass_.size()); }
  /// True when y's body key and feet's states are those of `key`; with `store`, writes them
  /// there first.
  bool same_key(const ode::Vec& y, Eigen::VectorXd& key, bool store) const;
  /// The minimum-norm solution of A f = b (A: 3 x legs) into f_.
  const Eigen::VectorXd& min_norm_solve(const Eigen::MatrixXd& A, const Eigen::Vector3d& b) const;

  const RobotModel& model_;
  const scene::PseudoRigid& settings_;
  pseudorigid::MechanismSystem sys_;
  std::vector<double> force_;
  std::vector<Eigen::Vector3d> push_;
  std::vector<bool> free_;
  std::vector<double> inv_mass_;
  int rotation_ = -1;                                 ///< rigid body: its rotation states in y
  int mech_dim_ = 0;                                  ///< the mechanism's states (sys_'s)
  int body_first_ = 0;                                ///< the body's first state in y
  int qs_states_ = 0;                                 ///< quasi-static feet: 2 per leg, else 0
  std::vector<double> rest_;                          ///< quasi-static legs' rest lengths [m]
  std::vector<bool> pinned_;                          ///< quasi-static feet on the ground
  std::vector<Eigen::Vector3d> dir_;                  ///< ... directions (body)
  std::vector<std::array<Eigen::Vector3d, 2>> slot_;  ///< ... slot normals (body; 0: none)
  bool locked_ = false;                               ///< (quasi-static feet) stance hips locked
  // (quasi-static feet) the body's friction, slip speed, stiffnesses and damping.
  double mu_ = 0.0, v_slip_ = 0.0, k_leg_ = 0.0, k_slot_ = 0.0, k_ground_ = 0.0, c_leg_ = 0.0;
  /// (quasi-static feet) the normal force a foot at the ground in the air must be pressed by
  /// to land (foot_event): 1e-3 of the weight per leg [N].
  double land_force_ = 0.0;
  // Scratch, written before it is read within one call (no state carried between calls): the
  // actuator forces and their differences, the feedback's leg forces, grounded legs,
  // directions, system and solution, and the Jacobian's perturbed state and triplets.
  mutable ode::Vec extra_, fp_, fm_;
  mutable std::vector<double> fb_;
  // (quasi-static feet) feedback()'s memo: the last kFeedbackMemo states, their fb_ and
  // results (a step reads the feedback at its opening, closing and end points, and the events
  // and monitors at the end again); dropped by the setters of what else it reads.
  static constexpr int kFeedbackMemo = 4;
  struct FeedbackMemo {
    ode::Vec y;
    std::vector<double> fb;
    bool on = false;
  };
  mutable std::array<FeedbackMemo, kFeedbackMemo> fb_memo_entries_;
  mutable int fb_memo_count_ = 0, fb_memo_next_ = 0;
  mutable bool fb_memo_ = false;
  // (quasi-static feet) stance_at()'s memo: its key and the pinned legs' stances.
  mutable Eigen::VectorXd st_key_;
  mutable std::vector<Stance> st_;
  mutable bool st_memo_ = false;
  Eigen::Vector2d stance_tilt_ = Eigen::Vector2d::Zero();
  mutable std::vector<size_t> grounded_;  ///< feedback(): scratch (legs on the ground)
  mutable std::vector<Eigen::Vector3d> u_;
  mutable Eigen::MatrixXd A_;
  mutable Eigen::VectorXd f_;
  mutable ode::Vec yp_, y_damp_;
  mutable std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace pronk::robot
