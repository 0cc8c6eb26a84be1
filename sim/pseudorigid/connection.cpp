#include "sim/pseudorigid/connection.hpp"

#include <cmath>

namespace pronk::pseudorigid {

namespace {

/// The spring's and the damper's derivatives (before an actuator's clamp) into out->d_dx and
/// out->d_dv: at a separation of length l along the unit e (zero below epsilon), relative
/// velocity v, e.v = ev.
void law_derivatives(const Connection& c, double rest_length, const Eigen::Vector3d& v, double l,
                     const Eigen::Vector3d& e, bool has_dir, double ev, ConnectionForce* out) {
  const Eigen::Matrix3d eye = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d eet = e * e.transpose(), perp = eye - eet;
  Eigen::Matrix3d spring_dx = Eigen::Matrix3d::Zero();
  if (c.stiffness != 0.0) {
    if (rest_length == 0.0) {
      spring_dx = -c.stiffness * eye;
    } else if (has_dir) {
      spring_dx = -c.stiffness * (eet + ((l - rest_length) / l) * perp);
    }
  }
  Eigen::Matrix3d damper_dx = Eigen::Matrix3d::Zero(), damper_dv = Eigen::Matrix3d::Zero();
  if (c.damping != 0.0 && has_dir) {
    damper_dv = -c.damping * eet;
    damper_dx = -(c.damping / l) * (ev * perp + e * (perp * v).transpose());
  }
  out->d_dx = spring_dx + damper_dx;
  out->d_dv = damper_dv;
}

}  // namespace

ConnectionForce connection_force(const Connection& c, double rest_length, const Eigen::Vector3d& d,
                                 const Eigen::Vector3d& v, double epsilon, bool derivatives) {
  ConnectionForce out;
  const double l = d.norm();
  out.length = l;
  const bool has_dir = l >= epsilon;
  const Eigen::Vector3d e = has_dir ? Eigen::Vector3d(d / l) : Eigen::Vector3d::Zero();

  // Spring (and the actuator's proportional part).
  Eigen::Vector3d spring = Eigen::Vector3d::Zero();
  if (c.stiffness != 0.0) {
    if (rest_length == 0.0) {
      spring = -c.stiffness * d;
    } else if (has_dir) {
      spring = -c.stiffness * (l - rest_length) * e;
    } else {
      out.zero_length = true;
    }
  }
  // Damper along the connection.
  Eigen::Vector3d damper = Eigen::Vector3d::Zero();
  double ev = 0.0;
  if (c.damping != 0.0) {
    if (has_dir) {
      ev = e.dot(v);
      damper = -c.damping * ev * e;
    } else {
      out.zero_length = true;
    }
  }
  if (derivatives) law_derivatives(c, rest_length, v, l, e, has_dir, ev, &out);
  if (c.kind == ConnectionClass::kActuator) {
    // PD actuator: spring + damper terms form the command, clamped.
    Eigen::Vector3d cmd = spring + damper;
    if (c.force_limit > 0.0 && cmd.norm() > c.force_limit) {
      const double n = cmd.norm();
      const Eigen::Vector3d u = cmd / n;
      cmd = c.force_limit * u;
      if (derivatives) {
        const Eigen::Matrix3d proj =
            (c.force_limit / n) * (Eigen::Matrix3d::Identity() - u * u.transpose());
        out.d_dx = (proj * out.d_dx).eval();
        out.d_dv = (proj * out.d_dv).eval();
      }
    }
    out.force = cmd;
  } else {
    out.force = spring + damper;
    out.dissipative = damper;
  }
  // Linear friction and quadratic drag act along the relative velocity.
  if (c.friction != 0.0) {
    out.force -= c.friction * v;
    out.dissipative -= c.friction * v;
    if (derivatives) out.d_dv -= c.friction * Eigen::Matrix3d::Identity();
  }
  if (c.drag != 0.0) {
    const double s = v.norm();
    out.force -= c.drag * s * v;
    out.dissipative -= c.drag * s * v;
    if (derivatives && s > 0.0) {
      out.d_dv -= c.drag * (s * Eigen::Matrix3d::Identity() + v * v.transpose() / s);
    }
  }
  return out;
}

double connection_energy(const Connection& c, double rest_length, const Eigen::Vector3d& d) {
  if (c.kind == ConnectionClass::kActuator || c.stiffness == 0.0) return 0.0;
  return connection_energy_at(c, rest_length, d.norm());
}

double connection_energy_at(const Connection& c, double rest_length, double length) {
  if (c.kind == ConnectionClass::kActuator || c.stiffness == 0.0) return 0.0;
  const double stretch = rest_length == 0.0 ? length : length - rest_length;
  return 0.5 * c.stiffness * stretch * stretch;
}

}  // namespace pronk::pseudorigid
