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

  int dimension() const override { return sys_.dimension(); }
  void rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  bool has_jacobian() const override { return true; }
  void jacobian(double t, const ode::Vec& y, Eigen::SparseMatrix<double>& J) const override;
  bool autonomous() const override { return true; }
  void momentum_mask(ode::Vec& mask) const override { sys_.momentum_mask(mask); }
  void position_rate(const ode::Vec& y, ode::Vec& dydt) const override {
    sys_.position_rate(y, dydt);
  }
  double kinetic_energy(const ode::Vec& y) const override { return sys_.kinetic_energy(y); }
  int momentum_block() const override { return sys_.momentum_block(); }
  /// The mechanism's dissipation split. The actuator forces (the stance feedback's kd
  /// part included) stay in the kicks: they act on the body's rotation, kd / I ~ 1e2 1/s,
  /// far from stiff at the steps the springs allow.
  bool has_dissipation_split() const override { return sys_.has_dissipation_split(); }
  bool has_drift() const override { return sys_.has_drift(); }
  void drift(double h, ode::Vec& y) const override { sys_.drift(h, y); }
  void conservative_rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  double dissipate(double t, double h, const ode::Vec& y_ref, ode::Vec& y) const override {
    return sys_.dissipate(t, h, y_ref, y);
  }
  void correct_step(const ode::Vec& y0, ode::Vec& y1) const override { sys_.correct_step(y0, y1); }

  /// Signed actuator force of each leg [N] (positive pushes the body away from
  /// the foot) along the unit body-frame push direction `push` (= -leg direction).
  void set_actuators(const std::vector<double>& force, const std::vector<Eigen::Vector3d>& push) {
    force_ = force;
    push_ = push;
  }
  const std::vector<double>& actuator_forces() const { return force_; }
  /// The tilt the stance attitude feedback holds: roll and pitch [rad] (small angles, about
  /// body x and y; 0 by default: level). The attitude integral action sets it per stride.
  void set_stance_tilt(const Eigen::Vector2d& tilt) { stance_tilt_ = tilt; }
  /// Each leg's total actuator force at y [N]: the set force plus, for a grounded
  /// leg, the stance attitude feedback (settings stance_kp, stance_kd).
  std::vector<double> actuator_forces(const ode::Vec& y) const;
  /// Frees leg i's hip (stance with rotating hips: the slide becomes a slot) or
  /// locks it. A free leg's actuator pushes along the current foot -> hip line (like
  /// the leg spring), not along `push`.
  void set_free(size_t i, bool free) { free_[i] = free; }
  bool free(size_t i) const { return free_[i]; }
  /// Unit world direction of leg i's actuator push on the body (foot -> hip for a
  /// free leg, R push otherwise).
  Eigen::Vector3d push_world(size_t i, const ode::Vec& y) const;
  /// push_world with the body's rotation R at y already known.
  Eigen::Vector3d push_world(size_t i, const ode::Vec& y, const Eigen::Matrix3d& R) const;

  const pseudorigid::MechanismSystem& mechanism() const { return sys_; }
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
  bool feedback(const ode::Vec& y) const;
  /// The minimum-norm solution of A f = b (A: 3 x legs) into f_.
  const Eigen::VectorXd& min_norm_solve(const Eigen::MatrixXd& A, const Eigen::Vector3d& b) const;

  const RobotModel& model_;
  const scene::PseudoRigid& settings_;
  pseudorigid::MechanismSystem sys_;
  std::vector<double> force_;
  std::vector<Eigen::Vector3d> push_;
  std::vector<bool> free_;
  std::vector<double> inv_mass_;
  int rotation_ = -1;  ///< rigid body: its rotation states in y
  // Scratch, written before it is read within one call (no state carried between calls): the
  // actuator forces and their differences, the feedback's leg forces, grounded legs,
  // directions, system and solution, and the Jacobian's perturbed state and triplets.
  mutable ode::Vec extra_, fp_, fm_;
  mutable std::vector<double> fb_;
  Eigen::Vector2d stance_tilt_ = Eigen::Vector2d::Zero();
  mutable std::vector<size_t> grounded_;  ///< feedback(): scratch (legs on the ground)
  mutable std::vector<Eigen::Vector3d> u_;
  mutable Eigen::MatrixXd A_;
  mutable Eigen::VectorXd f_;
  mutable ode::Vec yp_;
  mutable std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace pronk::robot
