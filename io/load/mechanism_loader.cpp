#include "io/load/mechanism_loader.hpp"

#include <cmath>
#include <map>

#include "io/load/auto_solver_input.hpp"
#include "io/load/json_reader.hpp"
#include "sim/math/rotation.hpp"
#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/method_choice.hpp"

namespace pronk::io {

namespace pr = pronk::pseudorigid;

bool is_mechanism_document(const json& doc) {
  if (!doc.is_object()) return false;
  const auto it = doc.find("kind");
  return it != doc.end() && it->is_string() && it->get<std::string>() == "mechanism";
}

namespace {

/// The raw value of an optional key, nullptr when absent.
const json* raw(const json& node, const std::string& key) {
  if (!node.is_object()) return nullptr;
  const auto it = node.find(key);
  return it == node.end() ? nullptr : &*it;
}

/// The method of a scene that names none: chosen for the scene (method_choice.hpp).
constexpr const char* kDefaultMethod = "auto";

class Loader {
 private:
  struct Settings {
    bool internal_auto = false, contact_auto = false;
    double internal_stiffness = 1e6;  ///< [N/m]
    double contact_stiffness = 1e5;   ///< [N/m]
    double strain_budget = 1e-4;
    double penetration_budget = 1e-4;  ///< [m]
    double load_factor = 10.0;
    bool method_auto = false;  ///< "method": "auto" (method_choice.hpp)
    double accuracy = pr::AutoRequest{}.accuracy;
  };

 public:
  Loader(const json& doc, std::string file) : doc_(doc), file_(std::move(file)) {}

  LoadedMechanism run() {
    LoadedMechanism out;
    out.resolved = doc_;
    JsonReader r(doc_, file_, "");
    const std::string kind = r.choice_or("kind", "", {"mechanism"});
    if (kind.empty()) throw r.error("kind", "\"mechanism\"", "nothing");
    pr::Mechanism& m = out.mechanism;
    m.name = r.path_name_or("name", "mechanism");  // the default output directory out/<name>
    m.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
    if (r.has("gravity")) {
      m.gravity = r.vector("gravity", 3, -kMaxGravity, kMaxGravity);
    } else {
      r.optional("gravity");
    }

    // Simulation settings first: body and surface defaults come from there.
    Settings set;
    if (r.has("simulation")) {
      JsonReader s = r.object("simulation");
      read_simulation(s, doc_["simulation"], &m.simulation, &set);
      s.finish();
    } else {
      r.optional("simulation");
      const json empty = json::object();  // the reader keeps a reference: must outlive it
      JsonReader s(empty, file_, "/simulation");
      read_simulation(s, empty, &m.simulation, &set);
    }
    read_nodes(r, set, &m);
    read_elements(r, set, &m);
    r.finish();

    std::string err;
    if (!m.validate(&err)) throw r.error("", "a consistent mechanism", err);
    resolve_stiffness(set, &out);
    resolve_method(set, &out);
    write_resolved_simulation(set, &out);
    return out;
  }

 private:
  /// Masses, anchors and bodies (at least one mass).
  void read_nodes(JsonReader& r, const Settings& set, pr::Mechanism* mech) {
    pr::Mechanism& m = *mech;
    if (r.has("masses")) {
      for (JsonReader& e : r.object_array("masses")) {
        const std::string name = node_name(e);
        const double mass = e.number_or("mass", 1.0, kMinMass, kMaxMass);
        const Eigen::Vector3d x = e.vector("position", 3);
        const Eigen::Vector3d v = e.vec3_or("velocity", Eigen::Vector3d::Zero());
        define(e, name, pr::add_mass(m, name, mass, x, v));
        e.finish();
      }
    } else {
      r.optional("masses");
    }
    if (r.has("anchors")) {
      for (JsonReader& e : r.object_array("anchors")) {
        const std::string name = node_name(e);
        define(e, name, pr::add_anchor(m, name, e.vector("position", 3)));
        e.finish();
      }
    } else {
      r.optional("anchors");
    }
    if (r.has("bodies")) {
      const auto bodies = r.object_array("bodies");
      for (size_t i = 0; i < bodies.size(); ++i) {
        read_body(bodies[i], doc_["bodies"][i], set, &m);
      }
    } else {
      r.optional("bodies");
    }
    if (m.masses.empty()) {
      throw r.error("", "at least one mass or body in \"masses\" or \"bodies\"", "none");
    }
  }

  /// Connections, surfaces, forces and actuators.
  void read_elements(JsonReader& r, const Settings& set, pr::Mechanism* m) {
    if (r.has("connections")) {
      for (JsonReader& e : r.object_array("connections")) read_connection(e, m);
    } else {
      r.optional("connections");
    }
    if (r.has("surfaces")) {
      for (JsonReader& e : r.object_array("surfaces")) read_surface(e, set, m);
    } else {
      r.optional("surfaces");
    }
    if (r.has("forces")) {
      for (JsonReader& e : r.object_array("forces")) read_force(e, m);
    } else {
      r.optional("forces");
    }
    if (r.has("actuators")) {
      for (JsonReader& e : r.object_array("actuators")) read_actuator(e, m);
    } else {
      r.optional("actuators");
    }
  }

  /// Stiffness: "auto" picks from the budgets, then the resolved document records numbers.
  void resolve_stiffness(const Settings& set, LoadedMechanism* loaded) const {
    LoadedMechanism& out = *loaded;
    pr::Mechanism& m = out.mechanism;
    pr::StiffnessSettings ss;
    ss.internal_auto = set.internal_auto;
    ss.contact_auto = set.contact_auto;
    ss.strain_budget = set.strain_budget;
    ss.penetration_budget = set.penetration_budget;
    ss.load_factor = set.load_factor;
    out.internal_auto = set.internal_auto;
    out.contact_auto = set.contact_auto;
    if (set.internal_auto || set.contact_auto) out.stiffness = pr::choose_stiffness(m, ss);
    if (set.internal_auto && !m.bodies.empty()) {
      // Per body: the stiffness of its first internal spring (all of a body's are equal).
      for (size_t b = 0; b < m.bodies.size(); ++b) {
        for (const pr::Connection& c : m.connections) {
          if (c.kind == pr::ConnectionClass::kInternal && c.a.kind == pr::NodeRef::Kind::kMass &&
              m.masses[c.a.index].body == static_cast<int>(b)) {
            out.resolved["bodies"][b]["internal_stiffness"] = c.stiffness;
            break;
          }
        }
      }
    }
  }

  /// "method": "auto": probes the built mechanism (stiffness resolved) and applies the choice.
  static void resolve_method(const Settings& set, LoadedMechanism* loaded) {
    loaded->method_auto = set.method_auto;
    if (!set.method_auto) return;
    pr::SimulationOptions& o = loaded->mechanism.simulation;
    pr::AutoRequest request;
    request.accuracy = set.accuracy;
    request.h_max = o.solver.h_max;
    request.t_end = o.t_end;
    loaded->method_choice = pr::choose_method(loaded->mechanism, request);
    pr::apply_choice(loaded->method_choice, &o.solver, &o.energy_tol);
  }

  /// The resolved document's "simulation": every setting explicit, "auto" replaced by the
  /// chosen numbers (stiffness) and the chosen method and its step or tolerances.
  static void write_resolved_simulation(const Settings& set, LoadedMechanism* loaded) {
    LoadedMechanism& out = *loaded;
    json& sim = out.resolved["simulation"];
    sim = simulation_json(out.mechanism.simulation, set);
    if (set.internal_auto && out.stiffness.internal_max > 0.0) {
      sim["internal_stiffness"] = out.stiffness.internal_max;
    }
    if (set.contact_auto) sim["contact_stiffness"] = out.stiffness.contact;
  }

  static json simulation_json(const pr::SimulationOptions& o, const Settings& s) {
    json j;
    j["t_end"] = o.t_end;
    j["output_interval"] = o.output_interval;
    j["method"] = std::string(ode::to_string(o.solver.method));
    j["accuracy"] = s.accuracy;
    j["rtol"] = o.solver.rtol;
    j["atol"] = o.solver.atol;
    j["h_fixed"] = o.solver.h_fixed;
    j["energy_tol"] = o.energy_tol;
    j["h_initial"] = o.solver.h_initial;
    j["h_max"] = o.solver.h_max;
    j["h_min"] = o.solver.h_min;
    j["max_steps"] = o.solver.max_steps;
    j["max_steps_per_second"] = o.solver.max_steps_per_second;
    j["dense_lu_max_dimension"] = o.solver.dense_lu_max_dimension;
    if (o.solver.method == ode::Method::kCvodeBdf) {
      j["cvode_linear_solver"] = std::string(ode::to_string(o.solver.cvode_linear_solver));
    }
    j["error_norm"] = o.error_norm == pr::ErrorNorm::kBody ? "body" : "state";
    j["euler_set"] = o.euler_313 ? "313" : "123";
    j["energy_blowup_factor"] = o.energy_blowup_factor;
    j["check_jacobian"] = o.check_jacobian;
    j["ghost_transfer"] =
        o.ghost_transfer == pr::GhostTransfer::kMinNorm ? "min_norm" : "barycentric";
    j["zero_length_epsilon"] = o.zero_length_epsilon;
    j["internal_stiffness"] = s.internal_stiffness;
    j["contact_stiffness"] = s.contact_stiffness;
    j["strain_budget"] = s.strain_budget;
    j["penetration_budget"] = s.penetration_budget;
    j["load_factor"] = s.load_factor;
    return j;
  }

  /// A stiffness given as a number > 0 or the string "auto"; returns true for auto.
  static bool stiffness_or_auto(JsonReader& s, const json& node, const std::string& key,
                                double* value) {
    const json* v = raw(node, key);
    if (v != nullptr && v->is_string()) {
      s.choice_or(key, "auto", {"auto"});
      return true;
    }
    if (v != nullptr && !v->is_number()) {
      s.optional(key);
      throw s.error(key, "a finite number > 0 or \"auto\"", describe(*v));
    }
    *value = s.positive_or(key, *value);
    return false;
  }

  void read_simulation(JsonReader& s, const json& node, pr::SimulationOptions* o, Settings* set) {
    o->t_end = s.positive_or("t_end", o->t_end);
    if (o->t_end > 1e6) throw s.error("t_end", "a duration <= 1e6 s", std::to_string(o->t_end));
    o->output_interval = s.positive_or("output_interval", o->output_interval);
    if (o->t_end / o->output_interval > 1e7) {
      throw s.error(
          "output_interval", "at most 1e7 output samples (t_end / output_interval)",
          std::to_string(o->output_interval) + " s for t_end " + std::to_string(o->t_end) + " s");
    }
    const std::string method = s.choice_or(
        "method", kDefaultMethod,
        {"auto", "euler", "rk2", "rk4", "dopri5", "rodas4", "radau5", "cvode_bdf", "verlet"});
    set->method_auto = method == "auto";
    if (!set->method_auto && !ode::parse_method(method, &o->solver.method)) {
      throw s.error("method", "a solver name", method);
    }
    set->accuracy = s.number_or("accuracy", set->accuracy, pr::kMinAccuracy, pr::kMaxAccuracy);
    if (set->method_auto) refuse_auto_chosen_settings(s, node);
    o->solver.rtol = s.positive_or("rtol", o->solver.rtol);
    o->solver.atol = s.positive_or("atol", o->solver.atol);
    o->solver.h_fixed = s.positive_or("h_fixed", o->solver.h_fixed);
    o->energy_tol = s.number_or("energy_tol", o->energy_tol, 0.0, 0.5);
    o->solver.h_initial = s.number_or("h_initial", o->solver.h_initial, 0.0);
    o->solver.h_max = s.positive_or("h_max", o->solver.h_max);
    o->solver.h_min = s.positive_or("h_min", o->solver.h_min);
    o->solver.max_steps = s.integer_or("max_steps", o->solver.max_steps, 1, 1000000000000L);
    o->solver.max_steps_per_second =
        s.number_or("max_steps_per_second", o->solver.max_steps_per_second, 0.0, 1e15);
    o->solver.dense_lu_max_dimension = static_cast<int>(
        s.integer_or("dense_lu_max_dimension", o->solver.dense_lu_max_dimension, 0, 1000000));
    ode::parse_cvode_linear_solver(
        s.choice_or("cvode_linear_solver", "auto", {"auto", "dense", "klu"}),
        &o->solver.cvode_linear_solver);
    o->error_norm = s.choice_or("error_norm", "state", {"state", "body"}) == "body"
                        ? pr::ErrorNorm::kBody
                        : pr::ErrorNorm::kState;
    o->euler_313 = s.choice_or("euler_set", "123", {"123", "313"}) == "313";
    o->energy_blowup_factor = s.positive_or("energy_blowup_factor", o->energy_blowup_factor);
    o->check_jacobian = s.boolean_or("check_jacobian", false);
    o->ghost_transfer =
        s.choice_or("ghost_transfer", "barycentric", {"barycentric", "min_norm"}) == "min_norm"
            ? pr::GhostTransfer::kMinNorm
            : pr::GhostTransfer::kBarycentric;
    o->zero_length_epsilon = s.positive_or("zero_length_epsilon", o->zero_length_epsilon);
    set->internal_auto = stiffness_or_auto(s, node, "internal_stiffness", &set->internal_stiffness);
    set->contact_auto = stiffness_or_auto(s, node, "contact_stiffness", &set->contact_stiffness);
    set->strain_budget = s.positive_or("strain_budget", set->strain_budget);
    set->penetration_budget = s.positive_or("penetration_budget", set->penetration_budget);
    set->load_factor = s.positive_or("load_factor", set->load_factor);
    o->strain_budget = set->strain_budget;  // also the thresholds of the run's warnings
    o->penetration_budget = set->penetration_budget;
    if (o->solver.h_max < o->solver.h_min) {
      throw s.error("h_max", "h_max >= h_min", std::to_string(o->solver.h_max));
    }
    std::string err;
    if (!o->validate(&err)) throw s.error("", "valid simulation settings", err);
  }

  static std::string node_name(JsonReader& e) {
    const std::string name = e.string_or("name", "");
    if (name.empty()) throw e.error("name", "a non-empty name", "nothing or \"\"");
    return name;
  }

  void define(JsonReader& e, const std::string& name, const pr::NodeRef& n) {
    if (!nodes_.emplace(name, n).second) {
      throw e.error("name", "a node name not used before", "duplicate \"" + name + "\"");
    }
  }

  pr::NodeRef node(JsonReader& e, const std::string& key) {
    const std::string name = e.string_or(key, "");
    const auto it = nodes_.find(name);
    if (it == nodes_.end()) {
      throw e.error(key,
                    "the name of a mass, body mass (\"<body>.0\"..\"<body>.3\"), ghost point "
                    "or anchor",
                    "\"" + name + "\"");
    }
    return it->second;
  }

  int body(JsonReader& e, const std::string& key) {
    const std::string name = e.string_or(key, "");
    const auto it = bodies_.find(name);
    if (it == bodies_.end()) throw e.error(key, "the name of a body", "\"" + name + "\"");
    return it->second;
  }

  static Eigen::Vector3d unit(JsonReader& e, const std::string& key,
                              const Eigen::Vector3d& fallback) {
    const Eigen::Vector3d d = e.vec3_or(key, fallback);
    if (!(d.norm() > 1e-12)) throw e.error(key, "a non-zero direction", "a zero vector");
    return d.normalized();
  }

  /// Initial world position of a node [m].
  Eigen::Vector3d initial_position(const pr::Mechanism& m, const pr::NodeRef& n) const {
    switch (n.kind) {
      case pr::NodeRef::Kind::kMass:
        return m.masses[n.index].position;
      case pr::NodeRef::Kind::kAnchor:
        return m.anchors[n.index].position;
      case pr::NodeRef::Kind::kGhost: {
        const pr::GhostPoint& g = m.ghost_points[n.index];
        const pr::Body& b = m.bodies[g.body];
        if (b.rigid) return m.masses[b.first_mass].position + b.attitude0 * g.local;
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int i = 0; i < 4; ++i) x += g.weights[i] * m.masses[b.first_mass + i].position;
        return x;
      }
    }
    return Eigen::Vector3d::Zero();
  }

  void read_body(const JsonReader& e0, const json& node, const Settings& set, pr::Mechanism* m) {
    JsonReader e = e0;
    pr::BodySpec spec;
    spec.name = node_name(e);
    if (bodies_.count(spec.name) != 0) {
      throw e.error("name", "a body name not used before", "duplicate \"" + spec.name + "\"");
    }
    spec.mass = e.number_or("mass", 1.0, kMinMass, kMaxMass);
    const json* inertia = raw(node, "inertia");
    if (inertia != nullptr && inertia->is_array() && !inertia->empty() &&
        (*inertia)[0].is_array()) {
      spec.inertia = e.matrix("inertia", 3, 3);
    } else {
      const Eigen::Vector3d p = e.vector("inertia", 3);
      spec.inertia = p.asDiagonal();
    }
    spec.com = e.vec3_or("com", Eigen::Vector3d::Zero());
    const Eigen::Vector3d angles = e.vec3_or("attitude_deg", Eigen::Vector3d::Zero()) * M_PI / 180;
    const bool s313 = e.choice_or("attitude_set", "123", {"123", "313"}) == "313";
    const math::EulerSet es = s313 ? math::EulerSet::k313 : math::EulerSet::k123;
    spec.attitude = math::euler_to_matrix(angles, es);
    spec.velocity = e.vec3_or("velocity", Eigen::Vector3d::Zero());
    if (e.has("omega") && e.has("euler_rates")) {
      throw e.error("euler_rates", "either \"omega\" or \"euler_rates\"", "both");
    }
    if (e.has("euler_rates")) {
      spec.omega = math::euler_rates_to_world_omega(angles, e.vector("euler_rates", 3), es);
      e.optional("omega");
    } else {
      spec.omega = e.vec3_or("omega", Eigen::Vector3d::Zero());
      e.optional("euler_rates");
    }
    if (e.has("internal_stiffness") && set.internal_auto) {
      throw e.error("internal_stiffness",
                    "no per-body stiffness while /simulation/internal_stiffness is \"auto\"",
                    describe(node["internal_stiffness"]));
    }
    spec.internal_stiffness = e.positive_or("internal_stiffness", set.internal_stiffness);
    spec.internal_damping = e.number_or("internal_damping", 0.0, 0.0);
    // One rigid body instead of four masses (rigid_body.hpp): the internal springs are unused.
    spec.rigid = e.boolean_or("rigid", false);
    std::string err;
    const int b = pr::add_body(*m, spec, &err);
    if (b < 0) throw e.error("inertia", "a valid inertia tensor", err);
    bodies_[spec.name] = b;
    if (spec.rigid && e.has("dummy_masses")) {
      throw e.error("dummy_masses", "no dummy masses on a rigid body", "dummy masses");
    }
    for (int i = 0; i < (spec.rigid ? 0 : 4); ++i) {
      define(e, spec.name + "." + std::to_string(i),
             pr::NodeRef{pr::NodeRef::Kind::kMass, m->bodies[b].first_mass + i});
    }
    if (e.has("ghost_points")) {
      for (JsonReader& g : e.object_array("ghost_points")) {
        const std::string name = node_name(g);
        define(g, name, pr::add_ghost_point(*m, b, name, g.vector("position", 3)));
        g.finish();
      }
    } else {
      e.optional("ghost_points");
    }
    if (e.has("reference_points")) {
      for (JsonReader& g : e.object_array("reference_points")) {
        const std::string name = node_name(g);
        pr::add_reference_point(*m, b, name, g.vector("position", 3));
        g.finish();
      }
    } else {
      e.optional("reference_points");
    }
    if (e.has("dummy_masses")) {
      for (JsonReader& g : e.object_array("dummy_masses")) {
        const std::string name = node_name(g);
        const Eigen::Vector3d x = g.vector("position", 3);
        const double ratio = g.number_or("ratio", 0.01, 1e-9, 1e3);
        define(g, name,
               pr::add_dummy_mass(*m, b, name, x, ratio, spec.internal_stiffness,
                                  spec.internal_damping));
        g.finish();
      }
    } else {
      e.optional("dummy_masses");
    }
    e.finish();
  }

  void read_connection(JsonReader& e, pr::Mechanism* m) {
    pr::Connection c;
    c.name = e.string_or("name", "connection" + std::to_string(m->connections.size()));
    c.a = node(e, "a");
    c.b = node(e, "b");
    if (c.a == c.b) throw e.error("b", "a node other than \"a\"", "the same node");
    const std::string cls = e.choice_or("class", "other", {"other", "leg", "internal", "actuator"});
    c.kind = cls == "leg"        ? pr::ConnectionClass::kLeg
             : cls == "internal" ? pr::ConnectionClass::kInternal
             : cls == "actuator" ? pr::ConnectionClass::kActuator
                                 : pr::ConnectionClass::kOther;
    c.stiffness = e.number_or("stiffness", 0.0, 0.0);
    const json* rl = raw(doc_at(e), "rest_length");
    if (rl != nullptr && rl->is_string()) {
      e.choice_or("rest_length", "initial", {"initial"});
      c.rest_length = (initial_position(*m, c.a) - initial_position(*m, c.b)).norm();
    } else {
      c.rest_length = e.number_or("rest_length", 0.0, 0.0);
    }
    c.damping = e.number_or("damping", 0.0, 0.0);
    c.friction = e.number_or("friction", 0.0, 0.0);
    c.drag = e.number_or("drag", 0.0, 0.0);
    c.force_limit = e.number_or("force_limit", 0.0, 0.0);
    if (c.stiffness == 0.0 && c.damping == 0.0 && c.friction == 0.0 && c.drag == 0.0) {
      throw e.error("", "at least one of stiffness, damping, friction, drag > 0", "none");
    }
    e.finish();
    m->connections.push_back(c);
  }

  /// The JSON node a reader reads (located by its pointer in the document).
  const json& doc_at(const JsonReader& e) const { return doc_.at(json::json_pointer(e.pointer())); }

  void read_surface(JsonReader& e, const Settings& set, pr::Mechanism* m) {
    pr::Surface s;
    s.name = e.string_or("name", "surface" + std::to_string(m->surfaces.size()));
    const std::string type = e.choice_or("type", "plane", {"plane", "line", "point"});
    s.type = type == "line"    ? pr::SurfaceType::kLine
             : type == "point" ? pr::SurfaceType::kPoint
                               : pr::SurfaceType::kPlane;
    const Eigen::Vector3d point = e.vec3_or("point", Eigen::Vector3d::Zero());
    if (e.has("body")) {
      s.body = body(e, "body");
      const pr::NodeRef g = pr::add_ghost_point(*m, s.body, s.name + ".point", point);
      s.ghost = g.index;
    } else {
      e.optional("body");
      s.point = point;
    }
    if (s.type == pr::SurfaceType::kPoint) {
      e.optional("direction");
      if (e.has("direction")) throw e.error("direction", "no direction for a point", "one");
    } else {
      s.direction = unit(e, "direction", Eigen::Vector3d::UnitZ());
    }
    if (e.has("stiffness") && set.contact_auto) {
      throw e.error("stiffness",
                    "no per-surface stiffness while /simulation/contact_stiffness is \"auto\"",
                    describe(doc_at(e)["stiffness"]));
    }
    s.stiffness = e.positive_or("stiffness", set.contact_stiffness);
    s.damping = e.number_or("damping", 0.0, 0.0);
    s.friction = e.number_or("friction", 0.0, 0.0, 10.0);
    s.slip_velocity = e.number_or("slip_velocity", s.slip_velocity, 1e-9, 10.0);
    if (s.friction > 0.0 && (s.type != pr::SurfaceType::kPlane || s.body >= 0)) {
      throw e.error("friction", "friction only on a grounded plane (0 elsewhere)",
                    describe(doc_at(e)["friction"]));
    }
    const json* nodes = raw(doc_at(e), "nodes");
    e.optional("nodes");
    if (nodes == nullptr || !nodes->is_array() || nodes->empty()) {
      throw e.error("nodes", "a non-empty array of node names",
                    nodes == nullptr ? "nothing" : describe(*nodes));
    }
    for (size_t i = 0; i < nodes->size(); ++i) {
      const json& n = (*nodes)[i];
      const std::string ptr = e.pointer_of("nodes") + "/" + std::to_string(i);
      const auto it = n.is_string() ? nodes_.find(n.get<std::string>()) : nodes_.end();
      if (it == nodes_.end()) {
        throw InputError(file_, ptr, "the name of a mass, body mass, ghost point or anchor",
                         describe(n));
      }
      if (it->second.kind == pr::NodeRef::Kind::kAnchor) {
        throw InputError(file_, ptr, "a node that can move (not an anchor)", describe(n));
      }
      s.nodes.push_back(it->second);
    }
    e.finish();
    m->surfaces.push_back(s);
  }

  void read_force(JsonReader& e, pr::Mechanism* m) {
    const std::string name = e.string_or(
        "name", "force" + std::to_string(m->world_forces.size() + m->body_forces.size()));
    const std::string frame = e.choice_or("frame", "world", {"world", "body"});
    const pr::NodeRef n = node(e, "node");
    if (n.kind == pr::NodeRef::Kind::kAnchor) {
      throw e.error("node", "a node that can move (not an anchor)", "an anchor");
    }
    const Eigen::Vector3d f = e.vector("force", 3);
    if (frame == "world") {
      m->world_forces.push_back(pr::WorldForce{name, n, f});
    } else {
      pr::BodyForce bf;
      bf.name = name;
      bf.node = n;
      bf.body = body(e, "body");
      bf.force = f;
      bf.t_start = e.number_or("t_start", 0.0, 0.0);
      bf.t_end = e.number_or("t_end", std::numeric_limits<double>::infinity(), bf.t_start);
      m->body_forces.push_back(bf);
    }
    e.finish();
  }

  void read_actuator(JsonReader& e, pr::Mechanism* m) {
    pr::ImpulseActuator a;
    a.name = e.string_or("name", "actuator" + std::to_string(m->impulse_actuators.size()));
    e.choice_or("type", "impulse", {"impulse"});
    a.node = node(e, "node");
    a.body = body(e, "body");
    a.direction = unit(e, "direction", Eigen::Vector3d::UnitZ());
    a.force = e.positive_or("force", 1.0);
    a.impulse = e.number("impulse", 0.0);
    a.t_start = e.number_or("t_start", 0.0, 0.0);
    e.finish();
    m->impulse_actuators.push_back(a);
  }

  const json& doc_;
  std::string file_;
  std::map<std::string, pr::NodeRef> nodes_;
  std::map<std::string, int> bodies_;
};

}  // namespace

LoadedMechanism parse_mechanism(const json& doc, const std::string& file) {
  if (!doc.is_object()) throw InputError(file, "", "a JSON object", describe(doc));
  return Loader(doc, file).run();
}

}  // namespace pronk::io
