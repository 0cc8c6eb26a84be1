// The resolved scene: a scene written back to JSON with every setting explicit.
#include <cmath>

#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"

namespace pronk::io {

using json = nlohmann::json;

namespace {
constexpr double kDeg = M_PI / 180.0;

json vec(const Eigen::VectorXd& v) {
  json a = json::array();
  for (int i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}
}  // namespace

json scene_to_json(const scene::Scene& s) {
  json j;
  j["name"] = s.name;
  j["model"] = std::string(scene::to_string(s.model));
  j["gravity"] = s.gravity;
  j["attitude"] =
      s.attitude == scene::AttitudeFormulation::kQuaternion ? "quaternion" : "small_angle_euler123";
  json I = json::array();
  for (int i = 0; i < 3; ++i) I.push_back(vec(s.body.inertia.row(i).transpose()));
  j["body"] = {{"mass", s.body.mass}, {"inertia_tensor", I}};
  json legs = {{"kind", s.legs.body_only ? "body_only" : "legged"}, {"length", s.legs.length}};
  if (!s.legs.body_only) {
    json hips = json::array();
    for (const auto& h : s.legs.hips) hips.push_back(vec(h));
    legs["hips"] = hips;
    json dis = json::array();
    for (size_t i = 0; i < s.legs.disabled.size(); ++i) {
      if (s.legs.disabled[i]) dis.push_back(i);
    }
    legs["disabled"] = dis;
  }
  j["legs"] = legs;
  const auto& c = s.controller;
  json gait = {{"kind", c.gait == scene::Gait::kAlternate ? "alternate" : "pronk"}};
  if (c.gait == scene::Gait::kAlternate) gait["groups"] = c.gait_groups;
  j["controller"] = {
      {"hop_height", c.hop_height},
      {"pulse_aware_hop", c.pulse_aware_hop},
      {"kp", vec(c.kp)},
      {"kd", vec(c.kd)},
      {"setpoint",
       {{"position", vec(c.setpoint_position)},
        {"velocity", vec(c.setpoint_velocity)},
        {"yaw_deg", c.setpoint_yaw / kDeg}}},
      {"bank",
       {{"enabled", c.bank_enabled},
        {"kp", c.bank_kp},
        {"kd", c.bank_kd},
        {"max_roll_deg", c.bank_max_roll / kDeg}}},
      {"allocation",
       {{"scheme",
         c.allocation.scheme == control::AllocationScheme::kSeed ? "seed" : "minimum_norm"},
        {"max_leg_impulse", c.allocation.max_leg_impulse},
        {"residual_tol", c.allocation.residual_tol}}},
      {"gait", gait}};
  if (!c.hop_height_changes.empty()) {
    json ch = json::array();
    for (const auto& [time, h] : c.hop_height_changes) {
      ch.push_back({{"time", time}, {"hop_height", h}});
    }
    j["controller"]["hop_height_changes"] = ch;
  }
  j["pulse"] = {{"mode", s.pulse.mode == scene::PulseMode::kDuration ? "duration" : "max_force"},
                {"max_force", s.pulse.max_force},
                {"duration", s.pulse.duration},
                {"gravity_compensation", s.pulse.gravity_compensation}};
  j["pseudo_rigid"] = pseudo_rigid_to_json(s.pseudo_rigid);
  if (s.model == scene::ModelKind::kMujoco) {
    j["mujoco"] = {
        {"timestep", s.mujoco.timestep},
        {"integrator", s.mujoco.integrator == scene::Mujoco::Integrator::kRk4 ? "rk4" : "euler"}};
  }
  const auto& q = s.initial.attitude;
  j["initial"] = {{"position", vec(s.initial.position)},
                  {"velocity", vec(s.initial.velocity)},
                  {"attitude_quaternion", {q.w(), q.x(), q.y(), q.z()}},
                  {"angular_velocity", vec(s.initial.angular_velocity)}};
  json d = json::array();
  for (const auto& x : s.disturbances) {
    d.push_back({{"time", x.time},
                 {"linear_impulse", vec(x.linear_impulse)},
                 {"angular_impulse", vec(x.angular_impulse)}});
  }
  j["disturbances"] = d;
  const auto& m = s.simulation;
  j["simulation"] = {
      {"duration", m.duration},
      {"max_strides", m.max_strides},
      {"sample_interval", m.sample_interval},
      {"solver",
       {{"method", std::string(ode::to_string(m.solver.method))},
        {"rtol", m.solver.rtol},
        {"atol", m.solver.atol},
        {"h_fixed", m.solver.h_fixed},
        {"h_max", m.solver.h_max},
        {"h_min", m.solver.h_min},
        {"h_initial", m.solver.h_initial},
        {"event_tol", m.solver.event_tol},
        {"max_steps", m.solver.max_steps},
        {"max_steps_per_second", m.solver.max_steps_per_second}}},
      {"fall", {{"min_height", m.fall_min_height}, {"max_tilt_deg", m.fall_max_tilt / kDeg}}}};
  return j;
}

std::string resolved_pointer_hint(const std::string& pointer) {
  const std::string inertia = "/body/inertia";
  if (pointer == inertia) return "; the resolved scene names it /body/inertia_tensor (a 3x3 array)";
  if (pointer.size() == inertia.size() + 2 && pointer.rfind(inertia + "/", 0) == 0 &&
      pointer.back() >= '0' && pointer.back() <= '2') {
    const std::string k(1, pointer.back());
    return "; the resolved scene names this principal moment /body/inertia_tensor/" + k + "/" + k;
  }
  if (pointer.rfind("/initial/attitude_deg", 0) == 0) {
    return "; the resolved scene holds the start attitude as /initial/attitude_quaternion (a "
           "study's scenarios tilt it with \"tilt_deg\")";
  }
  return "";
}

}  // namespace pronk::io
