#include "sim/mujoco/robot_mjcf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pronk::mujoco {

namespace {

/// x with 17 significant digits (MJCF round-trips the double).
std::string num(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

std::string nums(std::initializer_list<double> xs) {
  std::string s;
  for (double x : xs) s += (s.empty() ? "" : " ") + num(x);
  return s;
}

std::string nums(const std::vector<double>& xs) {
  std::string s;
  for (double x : xs) s += (s.empty() ? "" : " ") + num(x);
  return s;
}

std::string indexed(const char* stem, size_t i, const char* suffix) {
  return stem + std::to_string(i) + suffix;
}

void write_leg(std::ostringstream& o, const scene::Scene& s, const robot::RobotModel& model,
               size_t i) {
  const auto& mech = model.mechanism;
  const double L = s.legs.length;
  const double m_foot = mech.masses[static_cast<size_t>(model.foot[i])].mass;
  const auto& spring = mech.connections[static_cast<size_t>(model.leg_spring[i])];
  const Eigen::Vector3d& h = model.hip[i];
  const double I_foot = 0.4 * m_foot * kFootRadius * kFootRadius;
  o << "      <body name=\"" << leg_body_name(i) << "\" pos=\"" << nums({h.x(), h.y(), h.z()})
    << "\">\n"
    << "        <joint name=\"" << roll_joint_name(i) << "\" type=\"hinge\" axis=\"1 0 0\"/>\n"
    << "        <joint name=\"" << pitch_joint_name(i) << "\" type=\"hinge\" axis=\"0 1 0\"/>\n"
    << "        <joint name=\"" << slide_joint_name(i)
    << "\" type=\"slide\" axis=\"0 0 -1\" stiffness=\"" << num(spring.stiffness) << "\" damping=\""
    << num(spring.damping) << "\" springref=\"" << num(model.rest_length[i] - L) << "\"/>\n"
    << "        <inertial pos=\"0 0 " << num(-L) << "\" mass=\"" << num(m_foot)
    << "\" diaginertia=\"" << nums({I_foot, I_foot, I_foot}) << "\"/>\n"
    << "        <geom name=\"" << indexed("foot", i, "") << "\" type=\"sphere\" size=\""
    << num(kFootRadius) << "\" pos=\"0 0 " << num(-L)
    << "\" contype=\"1\" conaffinity=\"0\" mass=\"0\" rgba=\"0.2 0.2 0.2 1\"/>\n"
    << "        <geom type=\"capsule\" fromto=\"0 0 0 0 0 " << num(-L + kFootRadius)
    << "\" size=\"0.003\" contype=\"0\" conaffinity=\"0\" mass=\"0\" rgba=\"0.5 0.5 0.6 1\"/>\n"
    << "      </body>\n";
}

}  // namespace

const char* integrator_name(scene::Mujoco::Integrator integrator) {
  return integrator == scene::Mujoco::Integrator::kRk4 ? "RK4" : "Euler";
}

std::string leg_body_name(size_t i) { return indexed("leg", i, ""); }
std::string roll_joint_name(size_t i) { return indexed("leg", i, "_roll"); }
std::string pitch_joint_name(size_t i) { return indexed("leg", i, "_pitch"); }
std::string slide_joint_name(size_t i) { return indexed("leg", i, "_slide"); }
std::string roll_hold_name(size_t i) { return indexed("leg", i, "_roll_hold"); }
std::string pitch_hold_name(size_t i) { return indexed("leg", i, "_pitch_hold"); }
std::string thrust_name(size_t i) { return indexed("leg", i, "_thrust"); }

ContactParameters contact_parameters(const scene::Scene& s, double foot_mass) {
  ContactParameters c;
  const double k = s.pseudo_rigid.contact_stiffness, b = s.pseudo_rigid.contact_damping;
  c.omega = std::sqrt(k / foot_mass);
  const double zeta = b / (2.0 * std::sqrt(k * foot_mass));
  const double omega_max = 1.0 / (2.0 * s.mujoco.timestep);
  c.limited = c.omega > omega_max;
  const double w = std::min(c.omega, omega_max);
  c.stiffness = w * w;
  c.damping = 2.0 * zeta * w;
  return c;
}

std::string robot_mjcf(const scene::Scene& s, const robot::RobotModel& model,
                       const std::vector<double>& key_qpos, const std::vector<double>& key_qvel) {
  const auto& mech = model.mechanism;
  const size_t legs = model.hip.size();
  const double dt = s.mujoco.timestep;
  const double m_body = mech.masses[static_cast<size_t>(mech.bodies[model.body].first_mass)].mass;
  const double m_foot = legs > 0 ? mech.masses[static_cast<size_t>(model.foot[0])].mass : 0.0;
  const ContactParameters c = contact_parameters(s, m_foot);
  const Eigen::Matrix3d& I = s.body.inertia;
  const double mu = s.pseudo_rigid.friction;
  const std::string hold = "solref=\"" + nums({2.0 * dt, 1.0}) + "\" solimp=\"0.99 0.99 0.001\"";
  std::ostringstream o;
  o << "<!-- " << s.name
    << ": the robot of a pronk scene for MuJoCo (written by pronk; open it in MuJoCo's\n"
       "     viewer, e.g. `simulate robot.xml`). Body: rigid, the scene's mass and inertia; legs:\n"
       "     roll and pitch hinges and a spring-damper slide per hip; feet: spheres whose centres\n"
       "     touch the ground at z = 0. Contact reference per unit foot mass: K = "
    << num(c.stiffness) << " 1/s^2, B = " << num(c.damping) << " 1/s\n     (the scene's foot ";
  o << (c.limited ? "contact frequency " + num(c.omega) +
                        " rad/s is above 1 / (2 timestep) and is limited to it)"
                  : "contact as given)");
  o << ". -->\n"
    << "<mujoco model=\"" << s.name << "\">\n"
    << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "  <option timestep=\"" << num(dt) << "\" integrator=\""
    << integrator_name(s.mujoco.integrator) << "\" gravity=\"0 0 " << num(-s.gravity) << "\"/>\n"
    << "  <size nconmax=\"" << 2 * legs + 4 << "\" njmax=\"" << 8 * legs + 16 << "\"/>\n"
    << "  <worldbody>\n"
    << "    <light pos=\"0 0 3\" dir=\"0 0 -1\"/>\n"
    << "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 " << num(-kFootRadius)
    << "\" contype=\"0\" conaffinity=\"1\" condim=\"" << (mu > 0.0 ? 3 : 1) << "\" friction=\""
    << nums({mu, 0.0, 0.0}) << "\" solref=\"" << nums({-c.stiffness, -c.damping})
    << "\" solimp=\"0.99 0.99 0.001\" rgba=\"0.8 0.85 0.8 1\"/>\n"
    << "    <body name=\"body\" pos=\""
    << nums({s.initial.position.x(), s.initial.position.y(), s.initial.position.z()}) << "\">\n"
    << "      <freejoint name=\"root\"/>\n"
    << "      <inertial pos=\"0 0 0\" mass=\"" << num(m_body) << "\" fullinertia=\""
    << nums({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}) << "\"/>\n";
  double hx = 0.05, hy = 0.05;
  for (const Eigen::Vector3d& h : model.hip) {
    hx = std::max(hx, std::abs(h.x()));
    hy = std::max(hy, std::abs(h.y()));
  }
  o << "      <geom type=\"box\" size=\"" << nums({hx, hy, 0.02})
    << "\" contype=\"0\" conaffinity=\"0\" mass=\"0\" rgba=\"0.3 0.5 0.8 1\"/>\n";
  for (size_t i = 0; i < legs; ++i) write_leg(o, s, model, i);
  o << "    </body>\n  </worldbody>\n  <actuator>\n";
  for (size_t i = 0; i < legs; ++i) {
    o << "    <motor name=\"" << thrust_name(i) << "\" joint=\"" << slide_joint_name(i)
      << "\" gear=\"1\" ctrllimited=\"false\"/>\n";
  }
  o << "  </actuator>\n  <equality>\n";
  for (size_t i = 0; i < legs; ++i) {
    o << "    <joint name=\"" << roll_hold_name(i) << "\" joint1=\"" << roll_joint_name(i)
      << "\" polycoef=\"0 0 0 0 0\" " << hold << "/>\n"
      << "    <joint name=\"" << pitch_hold_name(i) << "\" joint1=\"" << pitch_joint_name(i)
      << "\" polycoef=\"0 0 0 0 0\" " << hold << "/>\n";
  }
  o << "  </equality>\n";
  if (!key_qpos.empty()) {
    o << "  <keyframe>\n    <key name=\"initial\" qpos=\"" << nums(key_qpos) << "\"";
    if (!key_qvel.empty()) o << " qvel=\"" << nums(key_qvel) << "\"";
    o << "/>\n  </keyframe>\n";
  }
  o << "</mujoco>\n";
  return o.str();
}

}  // namespace pronk::mujoco
