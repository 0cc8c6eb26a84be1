#include "io/load/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "io/load/json_reader.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scaled_settings.hpp"
#include "sim/reduced/run_limits.hpp"
#include "sim/scene/mujoco_scene.hpp"
#include "sim/scene/robot_scaling.hpp"

namespace pronk::io {

using json = nlohmann::json;
using scene::Vec3;

namespace {
constexpr double kDeg = M_PI / 180.0;

std::string number_text(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

// Checks the triangle inequalities of principal moments (a physical body).
void check_principal_moments(const Eigen::Vector3d& I, const JsonReader& r,
                             const std::string& key) {
  for (int i = 0; i < 3; ++i) {
    if (!(I[i] > 0.0)) {
      throw r.error(key, "positive principal moments of inertia",
                    "moment " + number_text(I[i]) + " kg m^2");
    }
  }
  for (int i = 0; i < 3; ++i) {
    const double others = I[(i + 1) % 3] + I[(i + 2) % 3];
    if (I[i] > others * (1.0 + 1e-12)) {
      static const char* names[] = {"Ixx", "Iyy", "Izz"};
      throw r.error(key,
                    "principal moments satisfying the triangle inequalities (each <= sum of "
                    "the other two)",
                    std::string(names[i]) + " = " + number_text(I[i]) + " > " +
                        number_text(others) + " (sum of the other two)");
    }
  }
}

scene::Body parse_body(JsonReader r) {
  scene::Body b;
  b.mass = r.number_or("mass", b.mass, kMinMass, kMaxMass);
  if (r.has("inertia") && r.has("inertia_tensor")) {
    throw r.error("inertia_tensor", "either \"inertia\" or \"inertia_tensor\", not both",
                  "both keys");
  }
  if (r.has("inertia_tensor")) {
    const std::string key = "inertia_tensor";
    const Eigen::Matrix3d I = r.matrix(key, 3, 3);
    if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-12 * I.cwiseAbs().maxCoeff()) {
      throw r.error(key, "a symmetric 3x3 matrix", "an asymmetric matrix");
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
    check_principal_moments(eig.eigenvalues(), r, key);
    b.inertia = 0.5 * (I + I.transpose());
  } else {
    Eigen::Vector3d I = r.has("inertia") ? Eigen::Vector3d(r.vector("inertia", 3))
                                         : Eigen::Vector3d(b.inertia.diagonal());
    check_principal_moments(I, r, "inertia");
    b.inertia = I.asDiagonal();
  }
  r.finish();
  return b;
}

}  // namespace

namespace {

void parse_scene_legs(JsonReader l, const std::string& file, scene::Legs* legs) {
  const std::string kind = l.choice_or("kind", "body_only", {"body_only", "legged"});
  legs->body_only = kind == "body_only";
  legs->length = l.positive_or("length", legs->length);
  if (!legs->body_only) {
    if (!l.has("hips")) throw l.error("hips", "an array of hip positions (legged)", "nothing");
    legs->hips = l.vec3_list("hips", 1, 64);
  } else if (l.has("hips")) {
    throw l.error("hips", "no hips for kind \"body_only\"", "hips");
  }
  legs->disabled.assign(legs->hips.size(), false);
  const std::vector<long> disabled = l.integer_array_or(
      "disabled", 0, std::max<long>(0, static_cast<long>(legs->hips.size()) - 1));
  if (legs->hips.empty() && !disabled.empty()) {
    // A body-only robot has no legs to disable (indexing `disabled` would be out of bounds).
    throw InputError(file, l.pointer_of("disabled") + "/0",
                     "no disabled legs (kind \"body_only\" has none)",
                     "number " + std::to_string(disabled[0]));
  }
  for (long i : disabled) legs->disabled[static_cast<size_t>(i)] = true;
  l.finish();
}

// The controller's optional sub-objects: setpoint, bank, allocation.
void parse_scene_setpoint_bank_allocation(JsonReader& c, scene::Controller* k,
                                          GivenSettings* given) {
  if (c.has("setpoint")) {
    JsonReader sp = c.object("setpoint");
    k->setpoint_position = sp.vec3_or("position", k->setpoint_position);
    k->setpoint_velocity = sp.vec3_or("velocity", k->setpoint_velocity);
    k->setpoint_yaw = sp.number_or("yaw_deg", 0.0, -360.0, 360.0) * kDeg;
    sp.finish();
  } else {
    c.optional("setpoint");
  }
  if (c.has("bank")) {
    JsonReader b = c.object("bank");
    given->bank = true;
    given->bank_kp = b.has("kp");
    given->bank_kd = b.has("kd");
    k->bank_enabled = b.boolean_or("enabled", true);
    k->bank_kp = b.number_or("kp", 0.0, 0.0, 1e6);
    k->bank_kd = b.number_or("kd", 0.0, 0.0, 1e6);
    k->bank_max_roll = b.number_or("max_roll_deg", k->bank_max_roll / kDeg, 1e-6, 89.0) * kDeg;
    b.finish();
  } else {
    c.optional("bank");
  }
  if (c.has("allocation")) {
    JsonReader a = c.object("allocation");
    const std::string scheme = a.choice_or("scheme", "minimum_norm", {"minimum_norm", "seed"});
    k->allocation.scheme = scheme == "seed" ? control::AllocationScheme::kSeed
                                            : control::AllocationScheme::kMinimumNorm;
    k->allocation.max_leg_impulse = a.number_or("max_leg_impulse", 0.0, 0.0, 1e9);
    k->allocation.residual_tol = a.number_or("residual_tol", k->allocation.residual_tol, 0.0, 1.0);
    a.finish();
  } else {
    c.optional("allocation");
  }
}

// The controller's schedule: hop height changes and the gait (leg groups need the legs).
void parse_scene_schedule_gait(JsonReader& c, const scene::Legs& legs, scene::Controller* k) {
  if (c.has("hop_height_changes")) {
    for (JsonReader h : c.object_array("hop_height_changes")) {
      const double time = h.number("time", 0.0, 1e9);
      k->hop_height_changes.emplace_back(time, h.positive_or("hop_height", k->hop_height));
      h.finish();
    }
    std::stable_sort(k->hop_height_changes.begin(), k->hop_height_changes.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
  } else {
    c.optional("hop_height_changes");
  }
  if (c.has("gait")) {
    JsonReader g = c.object("gait");
    const std::string kind = g.choice_or("kind", "pronk", {"pronk", "alternate"});
    k->gait = kind == "alternate" ? scene::Gait::kAlternate : scene::Gait::kPronk;
    if (k->gait == scene::Gait::kAlternate) {
      const long n = static_cast<long>(legs.hips.size());
      if (n == 0) throw g.error("kind", "a legged robot for an alternating gait", "body_only legs");
      if (!g.has("groups"))
        throw g.error("groups", "leg index groups, e.g. [[0,3],[1,2]]", "nothing");
      k->gait_groups = g.index_groups("groups", n - 1);
    } else {
      g.optional("groups");
    }
    g.finish();
  } else {
    c.optional("gait");
  }
}

void parse_scene_controller(JsonReader c, const scene::Legs& legs, scene::Controller* k,
                            GivenSettings* given) {
  k->hop_height = c.positive_or("hop_height", k->hop_height);
  k->pulse_aware_hop = c.boolean_or("pulse_aware_hop", false);
  refuse_both_gain_forms(c);
  given->kp = c.has("kp");
  given->kd = c.has("kd");
  if (given->kp) k->kp = c.vector("kp", 6, 0.0, 1e9);
  if (given->kd) k->kd = c.vector("kd", 6, 0.0, 1e9);
  c.optional("kp");
  c.optional("kd");
  if (c.has("gains")) {
    given->gains = parse_relative_gains(c.object("gains"));
  } else {
    c.optional("gains");
  }
  parse_scene_setpoint_bank_allocation(c, k, given);
  parse_scene_schedule_gait(c, legs, k);
  c.finish();
}

void parse_scene_pulse(JsonReader p, scene::Pulse* pulse) {
  const std::string mode = p.choice_or("mode", "max_force", {"max_force", "duration"});
  pulse->mode = mode == "duration" ? scene::PulseMode::kDuration : scene::PulseMode::kMaxForce;
  // Bounded away from 0: the leg force is impulse / duration.
  pulse->max_force = p.number_or("max_force", pulse->max_force, 1e-6, 1e9);
  pulse->duration = p.number_or("duration", pulse->duration, 1e-6, 1e3);
  pulse->gravity_compensation = p.boolean_or("gravity_compensation", true);
  p.finish();
}

void parse_scene_initial(JsonReader in, scene::Initial* initial) {
  initial->position = in.vec3_or("position", initial->position);
  initial->velocity = in.vec3_or("velocity", initial->velocity);
  initial->angular_velocity = in.vec3_or("angular_velocity", initial->angular_velocity);
  if (in.has("attitude_deg") && in.has("attitude_quaternion")) {
    throw in.error("attitude_quaternion", "either attitude_deg or attitude_quaternion", "both");
  }
  const std::string set = in.choice_or("euler_set", "123", {"123", "313"});
  if (in.has("attitude_deg")) {
    const Vec3 a = in.vector("attitude_deg", 3, -720.0, 720.0) * kDeg;
    initial->attitude =
        math::euler_to_quat(a, set == "313" ? math::EulerSet::k313 : math::EulerSet::k123);
  }
  if (in.has("attitude_quaternion")) {
    const Eigen::VectorXd q = in.vector("attitude_quaternion", 4, -1e3, 1e3);
    if (q.norm() < 1e-9)
      throw in.error("attitude_quaternion", "a non-zero quaternion [w, x, y, z]", "zero");
    initial->attitude = math::Quat(q[0], q[1], q[2], q[3]).normalized();
  }
  in.finish();
}

std::vector<scene::Disturbance> parse_scene_disturbances(std::vector<JsonReader> items) {
  std::vector<scene::Disturbance> out;
  for (JsonReader d : items) {
    scene::Disturbance dist;
    dist.time = d.number("time", 0.0, 1e9);
    dist.linear_impulse = d.vec3_or("linear_impulse", Vec3::Zero());
    dist.angular_impulse = d.vec3_or("angular_impulse", Vec3::Zero());
    d.finish();
    out.push_back(dist);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  return out;
}

void parse_scene_solver(JsonReader o, ode::SolverOptions* so) {
  const std::string method = o.choice_or("method", std::string(ode::to_string(so->method)),
                                         {"euler", "rk2", "rk4", "dopri5"});
  ode::parse_method(method, &so->method);
  so->rtol = o.positive_or("rtol", so->rtol);
  so->atol = o.positive_or("atol", so->atol);
  so->h_fixed = o.positive_or("h_fixed", so->h_fixed);
  so->h_max = o.positive_or("h_max", so->h_max);
  so->h_min = o.number_or("h_min", so->h_min, 0.0, 1.0);
  so->h_initial = o.number_or("h_initial", so->h_initial, 0.0, 1e3);
  so->event_tol = o.positive_or("event_tol", so->event_tol);
  so->max_steps = o.integer_or("max_steps", so->max_steps, 1, 1000000000000L);
  so->max_steps_per_second =
      o.number_or("max_steps_per_second", so->max_steps_per_second, 0.0, 1e15);
  std::string err;
  if (!so->validate(&err)) {
    const std::string field = err.substr(0, err.find(':'));
    throw o.error(field, "valid solver options", err);
  }
  o.finish();
}

void parse_scene_simulation(JsonReader m, scene::Simulation* sim) {
  sim->duration = m.number_or("duration", sim->duration, 1e-9, 1e7);
  sim->max_strides = m.integer_or("max_strides", sim->max_strides, 1, 1000000000L);
  sim->sample_interval = m.positive_or("sample_interval", sim->sample_interval);
  if (m.has("solver")) {
    parse_scene_solver(m.object("solver"), &sim->solver);
  } else {
    m.optional("solver");
  }
  if (m.has("fall")) {
    JsonReader f = m.object("fall");
    sim->fall_min_height = f.number_or("min_height", sim->fall_min_height, -1e6, 1e6);
    sim->fall_max_tilt = f.number_or("max_tilt_deg", sim->fall_max_tilt / kDeg, 1e-3, 180.0) * kDeg;
    f.finish();
  } else {
    m.optional("fall");
  }
  m.finish();
}

// The limits of sim/reduced/run_limits.hpp: the records a run holds (the CLI records the
// trajectory and the strides) and the fixed step of the model the scene runs in.
void check_run_limits(const scene::Scene& s, const std::string& file) {
  if (const auto b = reduced::memory_limit_breach(s.simulation, true, true)) {
    throw InputError(file, "/simulation/" + b->field, b->expected, b->found);
  }
  if (s.model == scene::ModelKind::kMujoco) return;  // MuJoCo's step: check_mujoco_scene
  const bool full = s.model == scene::ModelKind::kPseudoRigid;
  if (full && s.pseudo_rigid.solver_auto) return;  // auto chooses its own step
  if (const auto b =
          reduced::fixed_step_breach(s, full ? s.pseudo_rigid.solver : s.simulation.solver)) {
    throw InputError(file, full ? "/pseudo_rigid/solver/h_fixed" : "/simulation/solver/h_fixed",
                     b->expected, b->found);
  }
}

// "model": "mujoco" builds the robot with feet on slide joints (sim/scene/mujoco_scene.hpp).
void check_mujoco_scene(const scene::Scene& s, const std::string& file) {
  if (const auto r = scene::mujoco_refusal(s))
    throw InputError(file, r->pointer, r->expected, r->found);
}

// "mujoco": MuJoCo's integrator and step.
void parse_scene_mujoco(JsonReader r, scene::Mujoco* m) {
  m->timestep = r.number_or("timestep", m->timestep, 1e-6, 0.1);
  const std::string integrator = r.choice_or("integrator", "euler", {"euler", "rk4"});
  m->integrator =
      integrator == "rk4" ? scene::Mujoco::Integrator::kRk4 : scene::Mujoco::Integrator::kEuler;
  r.finish();
}

// The checks across sections, after every section is read.
void check_scene_consistency(const scene::Scene& s, const std::string& file) {
  if (s.controller.pulse_aware_hop && s.model == scene::ModelKind::kPulse &&
      s.pulse.mode != scene::PulseMode::kDuration) {
    throw InputError(
        file, "/controller/pulse_aware_hop",
        "false, or pulse mode \"duration\" (the law plans for a known stance duration)",
        "true with pulse mode \"max_force\"");
  }
  check_run_limits(s, file);
  if (s.model == scene::ModelKind::kMujoco) check_mujoco_scene(s, file);
  if (!(s.initial.position.z() > s.simulation.fall_min_height)) {
    throw InputError(
        file, "/initial/position/2",
        "a CoM height above the fall height " + number_text(s.simulation.fall_min_height) + " m",
        number_text(s.initial.position.z()));
  }
}

// The top-level scalars: name, model, gravity, attitude formulation.
void parse_scene_header(JsonReader& r, scene::Scene* s) {
  s->name = r.path_name_or("name", "scene");  // the default output directory out/<name>
  const std::string model = r.choice_or("model", "impulse", scene::model_names());
  s->model = scene::model_kind(model).value_or(scene::ModelKind::kImpulse);
  if (s->model == scene::ModelKind::kMujoco && !scene::mujoco_available()) {
    throw InputError(r.file(), "/model", scene::model_names_expected(), "\"mujoco\"");
  }
  s->gravity = r.number_or("gravity", 9.81, 0.0, 1e3);
  const std::string att =
      r.choice_or("attitude", "quaternion", {"quaternion", "small_angle_euler123"});
  s->attitude = att == "quaternion" ? scene::AttitudeFormulation::kQuaternion
                                    : scene::AttitudeFormulation::kSmallAngleEuler123;
}

// A legged scene without "initial" starts as a running design does: at the apex of its hop
// above the setpoint, level, moving at the setpoint velocity (a robot started at rest below
// its hop, behind a moving setpoint, spends its run catching up, or never hops).
void default_running_start(scene::Scene* s) {
  const scene::Vec3& p = s->controller.setpoint_position;
  const scene::Vec3& v = s->controller.setpoint_velocity;
  s->initial.position = scene::Vec3(p.x(), p.y(), s->legs.length + s->controller.hop_height);
  s->initial.velocity = scene::Vec3(v.x(), v.y(), 0.0);
}

}  // namespace

scene::Scene parse_scene(const json& doc, const std::string& file) {
  scene::Scene s;
  JsonReader r(doc, file, "");
  parse_scene_header(r, &s);
  if (r.has("body"))
    s.body = parse_body(r.object("body"));
  else
    r.optional("body");
  if (r.has("legs"))
    parse_scene_legs(r.object("legs"), file, &s.legs);
  else
    r.optional("legs");
  scene::seed_gains(s.body, &s.controller.kp, &s.controller.kd);
  GivenSettings given;  // what the scene says of the settings that scale with the robot
  if (r.has("controller"))
    parse_scene_controller(r.object("controller"), s.legs, &s.controller, &given);
  else
    r.optional("controller");
  if (r.has("pulse")) {
    parse_scene_pulse(r.object("pulse"), &s.pulse);
  } else {
    r.optional("pulse");
    if (!s.legs.body_only) {
      s.pulse.mode = scene::PulseMode::kDuration;
      s.pulse.duration = scene::default_pulse_duration(s);
    }
  }
  if (r.has("pseudo_rigid"))
    parse_pseudo_rigid(r.object("pseudo_rigid"), doc.at("pseudo_rigid"), &s.pseudo_rigid, &given);
  else
    r.optional("pseudo_rigid");
  if (r.has("mujoco"))
    parse_scene_mujoco(r.object("mujoco"), &s.mujoco);
  else
    r.optional("mujoco");
  if (r.has("initial")) {
    parse_scene_initial(r.object("initial"), &s.initial);
  } else {
    r.optional("initial");
    if (!s.legs.body_only) default_running_start(&s);
  }
  if (r.has("disturbances"))
    s.disturbances = parse_scene_disturbances(r.object_array("disturbances"));
  else
    r.optional("disturbances");
  s.simulation.fall_min_height = 0.4 * s.legs.length;
  if (r.has("simulation"))
    parse_scene_simulation(r.object("simulation"), &s.simulation);
  else
    r.optional("simulation");
  resolve_scaled_settings(given, file, &s);
  check_scene_consistency(s, file);
  r.finish();
  return s;
}

scene::Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  json doc = read_json_file(path);
  for (const auto& o : overrides) apply_override(doc, o);
  return parse_scene(doc, path);
}

}  // namespace pronk::io
