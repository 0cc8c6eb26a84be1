// The robot as an ODE system: the mechanism's own forces (MechanismSystem) plus
// the run-time inputs a controller drives: leg actuator forces (along each leg,
// on the hip and, for spring legs, the opposite force on the foot; along the
// current foot -> hip line while the leg's hip is free) and Coulomb
// friction on the feet, regularised F_t = -mu N v_t / sqrt(|v_t|^2 + v_s^2)
// with N the ground's normal force. The Jacobian is the mechanism's analytic one
// plus central differences of these extra forces over the states they read.
#pragma once

#include <vector>

#include "sim/pseudorigid/system.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"

namespace pronk::robot {

/// Power flows of the extra forces [W].
struct ExtraPower {
  double actuator = 0.0;  ///< work rate of the leg actuators
  double friction = 0.0;  ///< dissipated by foot friction (>= 0)
};

class RobotSystem final : public ode::OdeSystem {
 public:
  /// `mechanism` is the run's own copy of model.mechanism (hip placement turns its slides).
  RobotSystem(const RobotModel& model, const pseudorigid::Mechanism& mechanism,
              const scene::PseudoRigid& settings);

  int dimension() const override { return sys_.dimension(); }
  void rhs(double t, const ode::Vec& y, ode::Vec& dydt) const override;
  bool has_jacobian() const override { return true; }
  void jacobian(double t, const ode::Vec& y, Eigen::SparseMatrix<double>& J) const override;
  bool autonomous() const override { return true; }
  bool has_error_norm() const override { return sys_.has_error_norm(); }
  bool has_mechanical_split() const override { return true; }
  void momentum_mask(ode::Vec& mask) const override { sys_.momentum_mask(mask); }
  void position_rate(const ode::Vec& y, ode::Vec& dydt) const override {
    sys_.position_rate(y, dydt);
  }
  double error_norm(const ode::Vec& err, const ode::Vec& y0, const ode::Vec& y1, double rtol,
                    double atol) const override {
    return sys_.error_norm(err, y0, y1, rtol, atol);
  }

  /// Signed actuator force of each leg [N] (positive pushes the body away from
  /// the foot) along the unit body-frame push direction `push` (= -leg direction).
  void set_actuators(const std::vector<double>& force, const std::vector<Eigen::Vector3d>& push) {
    force_ = force;
    push_ = push;
  }
  const std::vector<double>& actuator_forces() const { return force_; }
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

  const pseudorigid::MechanismSystem& mechanism() const { return sys_; }
  ExtraPower power(const ode::Vec& y) const;
  /// Friction force on each foot (world) [N]; zero vectors off the ground.
  std::vector<Eigen::Vector3d> friction_forces(const ode::Vec& y) const;
  /// Ground normal force on each foot [N] (0 in the air).
  std::vector<double> normal_forces(const ode::Vec& y) const;

 private:
  /// Adds the extra forces into f (3 per mass); returns false when there are none.
  bool extra_forces(const ode::Vec& y, ode::Vec& f) const;
  double normal_force(const ode::Vec& y, int foot) const;
  /// Stance attitude feedback: fills fb_ with each leg's extra actuator force
  /// (zero for legs off the ground); false when it is off or no leg is grounded.
  bool feedback(const ode::Vec& y) const;

  const RobotModel& model_;
  const scene::PseudoRigid& settings_;
  const pseudorigid::Mechanism& mech_;  ///< the run's copy (leg rest lengths change)
  pseudorigid::MechanismSystem sys_;
  std::vector<double> force_;
  std::vector<Eigen::Vector3d> push_;
  std::vector<bool> free_;
  std::vector<double> inv_mass_;
  mutable ode::Vec extra_, fp_, fm_;
  mutable std::vector<double> fb_;
  mutable ode::Vec yp_;
  mutable std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace pronk::robot
