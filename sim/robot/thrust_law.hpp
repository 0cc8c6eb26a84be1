// The energy thrust law of spring legs: the constant leg-actuator force, fired at the bottom
// of the stance and held until the predicted lift-off, that sends the body to a target apex.
//
// Model (vertical, the legs' springs and dampers lumped, massless feet): from the bottom of the
// stance, CoM height z_b at rest, with the springs at rest at height z_rest,
//   m z'' = K (z_rest - z) - C z' + F - m g,
// until the legs' force K (z_rest - z) - C z' + F falls to zero (lift-off), then ballistic:
// apex = z_lo + z_lo'^2 / 2 g. The apex rises monotonically with F; the law finds F by
// bisection, each trial a fixed-step RK4 run of the model (a few hundred steps). The thrust
// runs only while the legs extend, so a force on for the whole thrust phase is not cut short
// by lift-off and no impulse is left to push the feet in the air.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace pronk::robot {

struct ThrustModel {
  double mass = 0.0;       ///< body mass [kg]
  double gravity = 9.81;   ///< [m/s^2]
  double stiffness = 0.0;  ///< K: the grounded legs' springs, vertical [N/m]
  double damping = 0.0;    ///< C: their dampers, vertical [N s/m]
  double z_bottom = 0.0;   ///< CoM height at the bottom [m]
  double z_rest = 0.0;     ///< CoM height with the springs at rest (> z_bottom) [m]
};

struct ThrustPlan {
  double force = 0.0;      ///< total actuator force, along the legs [N]
  double duration = 0.0;   ///< bottom to predicted lift-off [s]
  double apex = 0.0;       ///< predicted apex [m]
  bool saturated = false;  ///< the target lies outside [f_min, f_max]: the bound is returned
};

/// Prediction of the model above for a force F [N]: lift-off time (from the bottom) and apex.
ThrustPlan predict_thrust(const ThrustModel& m, double force);

/// The force in [f_min, f_max] whose predicted apex is `apex_target` [m].
ThrustPlan plan_thrust(const ThrustModel& m, double apex_target, double f_min, double f_max);

/// The legs' shares of a thrust: leg k pushes with force f_k along the unit vector u[k] at
/// arm[k] from the CoM (world). Returns the f closest to equal forces (least squares) whose
/// vertical sum is `vertical` [N] and whose moment about the CoM (x, y) is that of the forces
/// `planned` [N]; equal forces when fewer than three legs (or a degenerate stance) leave no
/// freedom.
std::vector<double> share_thrust(double vertical, const std::vector<Eigen::Vector3d>& u,
                                 const std::vector<Eigen::Vector3d>& arm,
                                 const std::vector<double>& planned);

}  // namespace pronk::robot
