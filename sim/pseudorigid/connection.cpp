#include "sim/pseudorigid/connection.hpp"

#include <cmath>

namespace pronk::pseudorigid {

ConnectionForce connection_force(const Connection& c, double rest_length, const Eigen::Vector3d& d,
                                 const Eigen::Vector3d& v, double epsilon, bool derivatives) {
  ConnectionForce out;
  const Eigen::Matrix3d eye = Eigen::Matrix3d::Identity();
  const double l = d.norm();
  const bool has_dir = l >= epsilon;
  const Eigen::Vector3d e = has_dir ? Eigen::Vector3d(d / l) : Eigen::Vector3d::Zero();
  Eigen::Matrix3d eet = Eigen::Matrix3d::Zero(), perp = Eigen::Matrix3d::Zero();
  if (derivatives) {
    eet = e * e.transpose();
    perp = eye - eet;
  }

  // Spring (and the actuator's proportional part).
  Eigen::Vector3d spring = Eigen::Vector3d::Zero();
  Eigen::Matrix3d spring_dx = Eigen::Matrix3d::Zero();
  if (c.stiffness != 0.0) {
    if (rest_length == 0.0) {
      spring = -c.stiffness * d;
      if (derivatives) spring_dx = -c.stiffness * eye;
    } else if (has_dir) {
      spring = -c.stiffness * (l - rest_length) * e;
      if (derivatives) spring_dx = -c.stiffness * (eet + ((l - rest_length) / l) * perp);
    } else {
      out.zero_length = true;
    }
  }
  // Damper along the connection.
  Eigen::Vector3d damper = Eigen::Vector3d::Zero();
  Eigen::Matrix3d damper_dx = Eigen::Matrix3d::Zero(), damper_dv = Eigen::Matrix3d::Zero();
  if (c.damping != 0.0) {
    if (has_dir) {
      const double ev = e.dot(v);
      damper = -c.damping * ev * e;
      if (derivatives) {
        damper_dv = -c.damping * eet;
        damper_dx = -(c.damping / l) * (ev * perp + e * (perp * v).transpose());
      }
    } else {
      out.zero_length = true;
    }
  }
  if (c.kind == ConnectionClass::kActuator) {
    // PD actuator: spring + damper terms form the command, clamped.
    Eigen::Vector3d cmd = spring + damper;
    Eigen::Matrix3d cmd_dx = spring_dx + damper_dx, cmd_dv = damper_dv;
    if (c.force_limit > 0.0 && cmd.norm() > c.force_limit) {
      const double n = cmd.norm();
      const Eigen::Vector3d u = cmd / n;
      const Eigen::Matrix3d proj = (c.force_limit / n) * (eye - u * u.transpose());
      cmd = c.force_limit * u;
      cmd_dx = proj * cmd_dx;
      cmd_dv = proj * cmd_dv;
    }
    out.force = cmd;
    out.d_dx = cmd_dx;
    out.d_dv = cmd_dv;
  } else {
    out.force = spring + damper;
    out.dissipative = damper;
    out.d_dx = spring_dx + damper_dx;
    out.d_dv = damper_dv;
  }
  // Linear friction and quadratic drag act along the relative velocity.
  if (c.friction != 0.0) {
    out.force -= c.friction * v;
    out.dissipative -= c.friction * v;
    out.d_dv -= c.friction * eye;
  }
  if (c.drag != 0.0) {
    const double s = v.norm();
    out.force -= c.drag * s * v;
    out.dissipative -= c.drag * s * v;
    if (s > 0.0) out.d_dv -= c.drag * (s * eye + v * v.transpose() / s);
  }
  return out;
}

double connection_energy(const Connection& c, double rest_length, const Eigen::Vector3d& d) {
  if (c.kind == ConnectionClass::kActuator || c.stiffness == 0.0) return 0.0;
  const double stretch = rest_length == 0.0 ? d.norm() : d.norm() - rest_length;
  return 0.5 * c.stiffness * stretch * stretch;
}

}  // namespace pronk::pseudorigid
