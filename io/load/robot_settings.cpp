#include "io/load/robot_settings.hpp"

#include <cmath>

#include "io/load/auto_solver_input.hpp"
#include "sim/pseudorigid/method_choice.hpp"

namespace pronk::io {

using json = nlohmann::json;
using Thrust = scene::PseudoRigid::Thrust;

namespace {

/// A stiffness given as a number > 0 or the string "auto"; returns true for auto.
bool stiffness_or_auto(JsonReader& r, const json& node, const std::string& key, double* value) {
  const auto it = node.find(key);
  if (it != node.end() && it->is_string()) {
    r.choice_or(key, "auto", {"auto"});
    return true;
  }
  if (it != node.end() && !it->is_number()) {
    r.optional(key);
    throw r.error(key, "a finite number > 0 or \"auto\"", describe(*it));
  }
  *value = r.positive_or(key, *value);
  return false;
}

// The leg spring: a stiffness [N/m], or {"stance_time": Ts} (the stiffness whose stance
// half-period is Ts, resolved with the body once the scene is read).
void parse_leg_stiffness(JsonReader& r, const json& node, scene::PseudoRigid* p,
                         GivenSettings* given) {
  const auto it = node.find("leg_stiffness");
  if (it != node.end() && it->is_object()) {
    JsonReader l = r.object("leg_stiffness");
    if (!l.has("stance_time"))
      throw l.error("stance_time", "the stance half-period the legs are sized for [s]", "nothing");
    given->leg_stance_time = l.number("stance_time", 1e-6, 1e3);
    l.finish();
    return;
  }
  given->leg_stiffness = it != node.end();
  if (it != node.end() && !it->is_number()) {
    r.optional("leg_stiffness");
    throw r.error("leg_stiffness", "a stiffness [N/m] or {\"stance_time\": seconds}",
                  describe(*it));
  }
  p->leg_stiffness = r.number_or("leg_stiffness", p->leg_stiffness, 1e-3, 1e9);
}

// Stance attitude feedback: absolute kp, kd [N m/rad, N m s/rad] (a missing one is 0), or
// "gains" per unit inertia; max_moment [N m] (0 = none). Left out, the robot-scaled defaults.
void parse_stance_attitude(JsonReader& r, scene::PseudoRigid* p, GivenSettings* given) {
  if (!r.has("stance_attitude")) {
    r.optional("stance_attitude");
    return;
  }
  given->stance_attitude = true;
  JsonReader a = r.object("stance_attitude");
  refuse_both_gain_forms(a);
  if (a.has("gains")) given->stance = parse_relative_stance_gains(a.object("gains"));
  const Eigen::VectorXd kp = a.has("kp") ? a.vector("kp", 2, 0.0, 1e6) : Eigen::VectorXd::Zero(2);
  const Eigen::VectorXd kd = a.has("kd") ? a.vector("kd", 2, 0.0, 1e6) : Eigen::VectorXd::Zero(2);
  if (!a.has("kp")) a.optional("kp");
  if (!a.has("kd")) a.optional("kd");
  if (!a.has("gains")) a.optional("gains");
  p->stance_max_moment = a.number_or("max_moment", 0.0, 0.0, 1e6);
  for (int k = 0; k < 2; ++k) {
    p->stance_kp[k] = kp[k];
    p->stance_kd[k] = kd[k];
  }
  a.finish();
}

// "hip_rotation": false (fixed hips), true or "neutral_point" (legs placed by the linear
// neutral-point rule), "pendulum" (the default: the stance solved as an inverted pendulum).
// A resolved scene writes true for the neutral-point rule, as scenes recorded before the
// pendulum rule did, so their hashes stand.
void parse_hip_rotation(JsonReader& r, const json& node, scene::PseudoRigid* p) {
  if (!r.has("hip_rotation")) {
    r.optional("hip_rotation");
    return;
  }
  const json& v = node.at("hip_rotation");
  if (v.is_boolean()) {
    p->hip_rotation = r.boolean_or("hip_rotation", p->hip_rotation);
    p->pendulum_placement = false;
    return;
  }
  if (!v.is_string()) {
    throw r.error("hip_rotation", "true, false, \"neutral_point\" or \"pendulum\"", describe(v));
  }
  p->hip_rotation = true;
  p->pendulum_placement =
      r.choice_or("hip_rotation", "pendulum", {"pendulum", "neutral_point"}) == "pendulum";
}

// The settings added after designs were first recorded, as the resolved scene writes them:
// pseudo_rigid_to_json leaves each out at its default, add_defaulted_settings puts it back.
json late_settings(const scene::PseudoRigid& p) {
  return {{"placement_trim_gain", p.placement_trim_gain},
          {"attitude_trim_max", p.attitude_trim_max},
          {"actuator_gain", p.actuator_gain},
          {"feet", p.feet == scene::PseudoRigid::Feet::kQuasiStatic ? "quasi_static" : "mass"},
          {"attitude_sensor_bias_deg",
           {p.attitude_sensor_bias[0] * 180.0 / M_PI, p.attitude_sensor_bias[1] * 180.0 / M_PI}}};
}

}  // namespace

void parse_pseudo_rigid(JsonReader r, const json& node, scene::PseudoRigid* out,
                        GivenSettings* given) {
  scene::PseudoRigid& p = *out;
  const std::string hips = r.choice_or("hips", "ghost_points", {"ghost_points", "dummy_masses"});
  p.hips =
      hips == "dummy_masses" ? scene::PseudoRigid::Hips::kDummy : scene::PseudoRigid::Hips::kGhost;
  // Rigid unless the scene asks for the body's flexibility (dummy-mass hips need four masses).
  const std::string body =
      r.choice_or("body", p.hips == scene::PseudoRigid::Hips::kDummy ? "four_masses" : "rigid",
                  {"four_masses", "rigid"});
  p.body = body == "rigid" ? scene::PseudoRigid::BodyKind::kRigid
                           : scene::PseudoRigid::BodyKind::kFourMasses;
  if (p.body == scene::PseudoRigid::BodyKind::kRigid &&
      p.hips == scene::PseudoRigid::Hips::kDummy) {
    throw r.error("hips",
                  "\"ghost_points\" with \"body\": \"rigid\" (a rigid body has no dummy masses)",
                  "\"dummy_masses\"");
  }
  p.dummy_ratio = r.number_or("dummy_ratio", p.dummy_ratio, 1e-6, 1.0);
  const std::string legs = r.choice_or("legs", "spring", {"spring", "force"});
  p.legs = legs == "force" ? scene::PseudoRigid::Legs::kForce : scene::PseudoRigid::Legs::kSpring;
  p.internal_auto = stiffness_or_auto(r, node, "internal_stiffness", &p.internal_stiffness);
  p.contact_auto = stiffness_or_auto(r, node, "contact_stiffness", &p.contact_stiffness);
  p.internal_damping = r.number_or("internal_damping", p.internal_damping, 0.0, 1e9);
  given->contact_damping = r.has("contact_damping");
  p.contact_damping = r.number_or("contact_damping", p.contact_damping, 0.0, 1e9);
  p.strain_budget = r.number_or("strain_budget", p.strain_budget, 1e-12, 0.5);
  p.penetration_budget = r.number_or("penetration_budget", p.penetration_budget, 1e-12, 1.0);
  p.feet = r.choice_or("feet", "mass", {"mass", "quasi_static"}) == "quasi_static"
               ? scene::PseudoRigid::Feet::kQuasiStatic
               : scene::PseudoRigid::Feet::kMass;
  given->foot_mass = r.has("foot_mass");
  p.foot_mass = r.number_or("foot_mass", p.foot_mass, 1e-6, 1e3);
  parse_leg_stiffness(r, node, &p, given);
  given->leg_damping = r.has("leg_damping");
  p.leg_damping = r.number_or("leg_damping", p.leg_damping, 0.0, 1e9);
  p.actuator_max_force = r.number_or("actuator_max_force", p.actuator_max_force, 0.0, 1e9);
  p.actuator_gain = r.number_or("actuator_gain", p.actuator_gain, 1e-3, 10.0);
  if (r.has("attitude_sensor_bias_deg")) {
    p.attitude_sensor_bias = r.vector("attitude_sensor_bias_deg", 2, -30.0, 30.0) * M_PI / 180.0;
  }
  p.impulse_feedback = r.boolean_or("impulse_feedback", p.impulse_feedback);
  p.actuators = r.boolean_or("actuators", p.actuators);
  p.body_error_norm =
      r.choice_or("error_norm", p.body_error_norm ? "body" : "state", {"state", "body"}) == "body";
  p.friction = r.number_or("friction", p.friction, 0.0, 10.0);
  p.slip_velocity = r.number_or("slip_velocity", p.slip_velocity, 1e-9, 10.0);
  parse_hip_rotation(r, node, &p);
  p.max_leg_angle =
      r.number_or("max_leg_angle_deg", p.max_leg_angle * 180.0 / M_PI, 0.0, 80.0) * M_PI / 180.0;
  parse_stance_attitude(r, &p, given);
  p.level_feet = r.boolean_or("level_feet", p.level_feet);
  p.hop_trim_gain = r.number_or("hop_trim_gain", p.hop_trim_gain, 0.0, 2.0);
  p.hop_trim_max = r.number_or("hop_trim_max", p.hop_trim_max, 0.0, 10.0);
  given->position_trim_gain = r.has("position_trim_gain");
  p.position_trim_gain = r.number_or("position_trim_gain", p.position_trim_gain, 0.0, 2.0);
  p.attitude_trim_gain = r.number_or("attitude_trim_gain", p.attitude_trim_gain, 0.0, 2.0);
  p.attitude_trim_max = r.number_or("attitude_trim_max", p.attitude_trim_max, 0.0, 1.0);
  p.placement_trim_gain = r.number_or("placement_trim_gain", p.placement_trim_gain, 0.0, 2.0);
  p.thrust = r.choice_or("thrust", std::string(p.thrust == Thrust::kEnergy ? "energy" : "impulse"),
                         {"impulse", "energy"}) == "energy"
                 ? Thrust::kEnergy
                 : Thrust::kImpulse;
  p.energy_blowup_factor = r.positive_or("energy_blowup_factor", p.energy_blowup_factor);
  if (r.has("solver")) {
    JsonReader o = r.object("solver");
    auto& so = p.solver;
    const std::string method = o.choice_or(
        "method", p.solver_auto ? "auto" : std::string(ode::to_string(so.method)),
        {"auto", "euler", "rk2", "rk4", "dopri5", "rodas4", "radau5", "cvode_bdf", "verlet"});
    p.solver_auto = method == "auto";
    if (!p.solver_auto) ode::parse_method(method, &so.method);
    p.accuracy =
        o.number_or("accuracy", p.accuracy, pseudorigid::kMinAccuracy, pseudorigid::kMaxAccuracy);
    if (p.solver_auto) refuse_auto_chosen_settings(o, node.at("solver"));
    so.rtol = o.positive_or("rtol", so.rtol);
    so.atol = o.positive_or("atol", so.atol);
    so.h_fixed = o.positive_or("h_fixed", so.h_fixed);
    so.h_flight = o.number_or("h_flight", so.h_flight, 0.0, 1.0);
    so.h_max = o.positive_or("h_max", so.h_max);
    so.h_min = o.number_or("h_min", so.h_min, 0.0, 1.0);
    so.h_initial = o.number_or("h_initial", so.h_initial, 0.0, 1e3);
    so.event_tol = o.positive_or("event_tol", so.event_tol);
    ode::parse_event_restart(
        o.choice_or("event_restart", std::string(ode::to_string(so.event_restart)),
                    {"interpolant", "step"}),
        &so.event_restart);
    so.max_steps = o.integer_or("max_steps", so.max_steps, 1, 1000000000000L);
    so.max_steps_per_second =
        o.number_or("max_steps_per_second", so.max_steps_per_second, 0.0, 1e15);
    p.energy_tol = o.number_or("energy_tol", p.energy_tol, 0.0, 0.5);
    std::string err;
    if (!so.validate(&err)) {
      const std::string field = err.substr(0, err.find(':'));
      throw o.error(field, "valid solver options", err);
    }
    o.finish();
  } else {
    r.optional("solver");
  }
  r.finish();
}

json pseudo_rigid_to_json(const scene::PseudoRigid& p) {
  const auto& so = p.solver;
  const std::string method = p.solver_auto ? "auto" : std::string(ode::to_string(so.method));
  json j = {{"hips", p.hips == scene::PseudoRigid::Hips::kDummy ? "dummy_masses" : "ghost_points"},
            {"body", p.body == scene::PseudoRigid::BodyKind::kRigid ? "rigid" : "four_masses"},
            {"dummy_ratio", p.dummy_ratio},
            {"legs", p.legs == scene::PseudoRigid::Legs::kForce ? "force" : "spring"},
            {"internal_damping", p.internal_damping},
            {"contact_damping", p.contact_damping},
            {"strain_budget", p.strain_budget},
            {"penetration_budget", p.penetration_budget},
            {"foot_mass", p.foot_mass},
            {"leg_stiffness", p.leg_stiffness},
            {"leg_damping", p.leg_damping},
            {"actuator_max_force", p.actuator_max_force},
            {"impulse_feedback", p.impulse_feedback},
            {"actuators", p.actuators},
            {"error_norm", p.body_error_norm ? "body" : "state"},
            {"friction", p.friction},
            {"slip_velocity", p.slip_velocity},
            {"hip_rotation",
             p.hip_rotation && p.pendulum_placement ? json("pendulum") : json(p.hip_rotation)},
            {"max_leg_angle_deg", p.max_leg_angle * 180.0 / M_PI},
            {"stance_attitude",
             {{"kp", {p.stance_kp[0], p.stance_kp[1]}},
              {"kd", {p.stance_kd[0], p.stance_kd[1]}},
              {"max_moment", p.stance_max_moment}}},
            {"level_feet", p.level_feet},
            {"hop_trim_gain", p.hop_trim_gain},
            {"hop_trim_max", p.hop_trim_max},
            {"thrust", p.thrust == Thrust::kEnergy ? "energy" : "impulse"},
            {"position_trim_gain", p.position_trim_gain},
            {"attitude_trim_gain", p.attitude_trim_gain},
            {"energy_blowup_factor", p.energy_blowup_factor},
            {"solver",
             {{"method", method},
              {"rtol", so.rtol},
              {"atol", so.atol},
              {"h_fixed", so.h_fixed},
              {"h_max", so.h_max},
              {"h_min", so.h_min},
              {"h_initial", so.h_initial},
              {"event_tol", so.event_tol},
              {"max_steps", so.max_steps},
              {"max_steps_per_second", so.max_steps_per_second},
              {"energy_tol", p.energy_tol}}}};
  // Absent at its default: the scenes recorded before it existed keep their hash.
  if (so.event_restart != ode::EventRestart::kInterpolant) {
    j["solver"]["event_restart"] = std::string(ode::to_string(so.event_restart));
  }
  if (so.h_flight > 0.0) j["solver"]["h_flight"] = so.h_flight;
  // "auto" stays "auto" in the resolved scene: the choice depends on the run. The settings
  // auto chooses are left out (the reader refuses them under auto).
  if (p.solver_auto) {
    j["solver"]["accuracy"] = p.accuracy;  // absent otherwise: unchanged
    for (const char* k : pseudorigid::kAutoChosenSettings) j["solver"].erase(k);
  }
  // Absent at their defaults: the scenes and studies recorded before they existed keep their
  // hash.
  const json late = late_settings(p), defaults = late_settings(scene::PseudoRigid{});
  for (const auto& [key, value] : late.items()) {
    if (value != defaults[key]) j[key] = value;
  }
  j["internal_stiffness"] = p.internal_auto ? json("auto") : json(p.internal_stiffness);
  j["contact_stiffness"] = p.contact_auto ? json("auto") : json(p.contact_stiffness);
  return j;
}

void add_defaulted_settings(json* resolved_scene) {
  if (!resolved_scene->contains("pseudo_rigid")) return;
  json& p = (*resolved_scene)["pseudo_rigid"];
  const json defaults =
      late_settings(scene::PseudoRigid{});  // items() needs it to outlive the loop
  for (const auto& [key, value] : defaults.items()) {
    if (!p.contains(key)) p[key] = value;
  }
}

namespace {
/// Spring legs (either full-model engine): the pulse settings their controller does not read.
void add_spring_leg_unused(const scene::Scene& s, std::vector<std::string>* out) {
  out->push_back("/pulse/gravity_compensation");
  // The energy thrust sizes and times the force itself: the planned impulses count, not the
  // pulse duration they were planned over (unless the hop law plans with it or a force limit
  // stretches the pulses).
  if (s.pseudo_rigid.thrust == Thrust::kEnergy && !s.controller.pulse_aware_hop &&
      s.pseudo_rigid.actuator_max_force == 0.0) {
    out->push_back("/pulse/duration");
  }
}

/// "model": "mujoco": MuJoCo steps the robot with its rigid body, joint hips and its own contact
/// solver, so the pseudo-rigid engine's body, hips, slides, friction regularisation and solver
/// settings do nothing; the legs, feet, contact, friction and controller settings are used.
std::vector<std::string> mujoco_unused_settings(const scene::Scene& s) {
  std::vector<std::string> out = {"/attitude", "/simulation/solver"};
  for (const char* k :
       {"body", "hips", "dummy_ratio", "internal_stiffness", "internal_damping", "strain_budget",
        "penetration_budget", "slip_velocity", "energy_blowup_factor", "error_norm", "solver"}) {
    out.push_back(std::string("/pseudo_rigid/") + k);
  }
  add_spring_leg_unused(s, &out);
  if (!s.pseudo_rigid.hip_rotation) out.push_back("/pseudo_rigid/level_feet");
  return out;
}
}  // namespace

std::vector<std::string> unused_settings(const scene::Scene& s) {
  std::vector<std::string> out;
  switch (s.model) {
    case scene::ModelKind::kMujoco:
      out = mujoco_unused_settings(s);
      break;
    case scene::ModelKind::kImpulse:
      out = {"/pulse", "/pseudo_rigid"};
      if (!s.controller.hop_height_changes.empty()) {
        out.push_back("/controller/hop_height_changes");
      }
      break;
    case scene::ModelKind::kPulse:
      out = {"/pseudo_rigid"};
      if (!s.controller.hop_height_changes.empty()) {
        out.push_back("/controller/hop_height_changes");
      }
      break;
    case scene::ModelKind::kPseudoRigid:
      out = {"/attitude", "/simulation/solver"};
      if (s.pseudo_rigid.legs == scene::PseudoRigid::Legs::kSpring) add_spring_leg_unused(s, &out);
      if (s.pseudo_rigid.hips == scene::PseudoRigid::Hips::kGhost) {
        out.push_back("/pseudo_rigid/dummy_ratio");
      }
      if (s.pseudo_rigid.body == scene::PseudoRigid::BodyKind::kRigid) {
        // No internal springs: internal_stiffness and internal_damping hold only the leg
        // slides (none with force legs); the strain budget bounds nothing (no strain) unless
        // "auto" sizes the slides with it; the rigid states are body-level already.
        out.push_back("/pseudo_rigid/error_norm");
        if (!s.pseudo_rigid.internal_auto) out.push_back("/pseudo_rigid/strain_budget");
        if (s.pseudo_rigid.legs == scene::PseudoRigid::Legs::kForce) {
          out.push_back("/pseudo_rigid/internal_stiffness");
          out.push_back("/pseudo_rigid/internal_damping");
        }
      }
      if (s.pseudo_rigid.solver_auto) {
        // auto chooses the method with its step or tolerances and verlet's energy budget.
        for (const char* k : {"rtol", "atol", "h_fixed", "energy_tol"}) {
          out.push_back(std::string("/pseudo_rigid/solver/") + k);
        }
      } else if (s.pseudo_rigid.solver.method != ode::Method::kVerlet) {
        out.push_back("/pseudo_rigid/solver/energy_tol");     // verlet's energy budget
        out.push_back("/pseudo_rigid/solver/event_restart");  // verlet's restart at events
      }
      // Verlet's flight step: only quasi-static feet have a flight without stiff modes
      // (listed when set: the scenes recorded before it existed keep their lists).
      if (s.pseudo_rigid.solver.h_flight > 0.0 &&
          (s.pseudo_rigid.solver_auto || s.pseudo_rigid.solver.method != ode::Method::kVerlet ||
           s.pseudo_rigid.feet != scene::PseudoRigid::Feet::kQuasiStatic ||
           s.pseudo_rigid.legs == scene::PseudoRigid::Legs::kForce)) {
        out.push_back("/pseudo_rigid/solver/h_flight");
      }
      if (s.pseudo_rigid.legs == scene::PseudoRigid::Legs::kForce) {
        for (const char* k :
             {"feet", "foot_mass", "leg_stiffness", "leg_damping", "contact_stiffness",
              "contact_damping", "friction", "slip_velocity", "hip_rotation", "stance_attitude",
              "level_feet", "hop_trim_gain", "hop_trim_max", "thrust"}) {
          out.push_back(std::string("/pseudo_rigid/") + k);
        }
      } else if (!s.pseudo_rigid.hip_rotation) {
        out.push_back("/pseudo_rigid/level_feet");  // levels the feet when placing the legs
      }
      if (s.pseudo_rigid.legs == scene::PseudoRigid::Legs::kSpring &&
          s.pseudo_rigid.feet == scene::PseudoRigid::Feet::kQuasiStatic) {
        // A massless foot: no mass, and nothing for the ground's damper to damp (the ground
        // spring stays, in series with the leg).
        out.push_back("/pseudo_rigid/foot_mass");
        out.push_back("/pseudo_rigid/contact_damping");
      }
      break;
  }
  return out;
}

}  // namespace pronk::io
