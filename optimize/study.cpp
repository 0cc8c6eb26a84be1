#include "optimize/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "io/load/json_reader.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize {

using nlohmann::json;

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {
constexpr double kDeg = M_PI / 180.0;

Aggregate parse_aggregate(io::JsonReader& r, const std::string& fallback) {
  const std::string a = r.choice_or("aggregate", fallback, {"mean", "worst", "cvar"});
  return a == "worst" ? Aggregate::kWorst : a == "cvar" ? Aggregate::kCvar : Aggregate::kMean;
}

std::string metric_of(io::JsonReader& r) {
  const std::string m = r.string_or("metric", "");
  if (!is_metric(m)) {
    std::string known;
    for (const auto& n : metric_names(scene::ModelKind::kPseudoRigid))
      known += (known.empty() ? "" : ", ") + n;
    throw r.error("metric", "a metric name (" + known + ")", "\"" + m + "\"");
  }
  return m;
}

// A [lo, hi] range with 0 <= lo <= hi, scaled.
void range(io::JsonReader& r, const std::string& key, double scale, double* lo, double* hi) {
  if (!r.has(key)) {
    r.optional(key);
    return;
  }
  const Eigen::VectorXd v = r.vector(key, 2, 0.0, 1e6);
  if (v[0] > v[1]) throw r.error(key, "[lo, hi] with lo <= hi", "lo > hi");
  *lo = v[0] * scale;
  *hi = v[1] * scale;
}

Scenario parse_scenario(io::JsonReader r, long index) {
  Scenario s;
  s.name = r.string_or("name", "scenario_" + std::to_string(index));
  s.position_offset = r.vec3_or("position_offset", s.position_offset);
  s.velocity_kick = r.vec3_or("velocity_kick", s.velocity_kick);
  s.tilt = r.vec3_or("tilt_deg", Eigen::Vector3d::Zero()) * kDeg;
  s.angular_velocity = r.vec3_or("angular_velocity", s.angular_velocity);
  s.duration = r.number_or("duration", 0.0, 0.0, 1e6);
  s.strides = r.integer_or("strides", 0, 0, 10000000);  // reduced::kMaxStrides
  if (r.has("disturbances")) {
    for (io::JsonReader d : r.object_array("disturbances")) {
      scene::Disturbance dist;
      dist.time = d.number("time", 0.0, 1e9);
      dist.linear_impulse = d.vec3_or("linear_impulse", Eigen::Vector3d::Zero());
      dist.angular_impulse = d.vec3_or("angular_impulse", Eigen::Vector3d::Zero());
      d.finish();
      s.disturbances.push_back(dist);
    }
  } else {
    r.optional("disturbances");
  }
  r.finish();
  return s;
}

// A scenario set: default duration/strides, an explicit list and/or random samples (which
// may perturb the robot's own numbers, checked against the nominal scene).
void parse_scenario_set(io::JsonReader s, const PerturbationContext& robot, ScenarioSet& set) {
  set.duration = s.number_or("duration", 5.0, 1e-6, 1e6);
  set.strides = s.integer_or("strides", 0, 0, 10000000);  // reduced::kMaxStrides
  set.compare_nominal = s.boolean_or("compare_nominal", true);
  if (s.has("list")) {
    long i = 0;
    for (io::JsonReader one : s.object_array("list"))
      set.scenarios.push_back(parse_scenario(one, i++));
  } else {
    s.optional("list");
  }
  if (s.has("random")) {
    io::JsonReader rr = s.object("random");
    RandomScenarios spec;
    spec.count = rr.integer_or("count", 0, 0, 1000000);
    spec.seed = static_cast<std::uint64_t>(rr.integer_or("seed", 1, 0, 9007199254740991L));
    range(rr, "tilt_deg", kDeg, &spec.tilt_lo, &spec.tilt_hi);
    range(rr, "offset", 1.0, &spec.offset_lo, &spec.offset_hi);
    range(rr, "lateral_offset", 1.0, &spec.lateral_lo, &spec.lateral_hi);
    range(rr, "velocity_kick", 1.0, &spec.kick_lo, &spec.kick_hi);
    range(rr, "yaw_deg", kDeg, &spec.yaw_lo, &spec.yaw_hi);
    range(rr, "angular_velocity", 1.0, &spec.spin_lo, &spec.spin_hi);
    spec.perturb = parse_perturbations(rr, robot);
    rr.finish();
    add_random_scenarios(spec, set);
  } else {
    s.optional("random");
  }
  s.finish();
  if (set.scenarios.empty())
    throw s.error("", "at least one scenario (\"list\" or \"random\")", "none");
}

// One design parameter, bound to a number of the resolved scene that its model uses.
Parameter parse_parameter(io::JsonReader& p, const json& resolved,
                          const std::vector<std::string>& unused, scene::ModelKind model) {
  Parameter par;
  par.name = p.string_or("name", "");
  if (par.name.empty()) throw p.error("name", "a parameter name", "nothing");
  par.pointer = p.string_or("pointer", "");
  // The resolved scene holds every number explicitly: the pointer must name one.
  const json* target = io::find_pointer(resolved, par.pointer);
  if (par.pointer.empty() || target == nullptr || !target->is_number()) {
    throw p.error("pointer", "a pointer to a number of the scene format (see scene.resolved.json)",
                  "\"" + par.pointer + "\", which names no number of a scene" +
                      io::resolved_pointer_hint(par.pointer));
  }
  // Tuning a number the model ignores would give a flat cost surface: refuse it.
  if (const std::string* u = ignored_setting(unused, par.pointer)) {
    throw p.error("pointer",
                  "a setting the " + std::string(scene::to_string(model)) +
                      " model uses (parameter \"" + par.name + "\")",
                  "\"" + par.pointer + "\", which that model ignores (" + *u + ")");
  }
  par.lower = p.number("lower");
  par.upper = p.number("upper");
  if (!(par.upper > par.lower))
    throw p.error("upper", "a number > lower", std::to_string(par.upper));
  par.log_scale = p.boolean_or("log", false);
  if (par.log_scale && !(par.lower > 0)) {
    throw p.error("lower", "a positive lower bound for a log-scaled parameter",
                  std::to_string(par.lower));
  }
  // The start is the scene's own value (its default when the scene does not set it),
  // unless "initial" says otherwise; a start outside the bounds is an error, not a clamp.
  const double current = target->get<double>();
  if (!p.has("initial") && !(current >= par.lower && current <= par.upper)) {
    throw p.error("initial",
                  "a start within [lower, upper] for parameter \"" + par.name +
                      "\": the scene's value is outside, so set \"initial\" or widen the bounds",
                  "no \"initial\", and the scene's value " + io::describe(json(current)) +
                      " outside [" + io::describe(json(par.lower)) + ", " +
                      io::describe(json(par.upper)) + "]");
  }
  par.initial = p.number_or("initial", current, par.lower, par.upper);
  p.finish();
  return par;
}

}  // namespace

json read_study_scene(io::JsonReader& r, const json& doc, const std::string& file,
                      const std::string& base_dir, std::string* scene_file) {
  *scene_file = file + "#/scene";
  if (!r.has("scene"))
    throw r.error("scene", "a scene file path or an inline scene object", "nothing");
  const json& sv = doc.at("scene");
  r.optional("scene");
  if (sv.is_string()) {
    std::filesystem::path p(sv.get<std::string>());
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    *scene_file = p.lexically_normal().string();
    return io::read_json_file(*scene_file);
  }
  if (!sv.is_object())
    throw r.error("scene", "a scene file path or an inline scene object", io::describe(sv));
  return sv;
}

void apply_study_scene_overrides(io::JsonReader& r, const json& doc, const std::string& file,
                                 json* scene_doc) {
  if (r.has("scene_overrides")) {
    const json& ov = doc.at("scene_overrides");
    r.optional("scene_overrides");
    if (!ov.is_array())
      throw r.error("scene_overrides", "an array of \"/ptr=value\" strings", io::describe(ov));
    for (size_t i = 0; i < ov.size(); ++i) {
      if (!ov[i].is_string()) {
        throw io::InputError(file, "/scene_overrides/" + std::to_string(i),
                             "a \"/ptr=value\" string", io::describe(ov[i]));
      }
      io::apply_override(*scene_doc, ov[i].get<std::string>());
    }
  } else {
    r.optional("scene_overrides");
  }
}

namespace {

// Parameters bind into the resolved scene (every number explicit) and must leave a valid scene.
void parse_study_parameters(io::JsonReader& r, const scene::Scene& scene0, const json& resolved,
                            EvaluatorConfig* ec) {
  const std::vector<std::string> unused = io::unused_settings(scene0);
  for (io::JsonReader p : r.object_array("parameters")) {
    Parameter par = parse_parameter(p, resolved, unused, scene0.model);
    ec->scene_doc[json::json_pointer(par.pointer)] = par.initial;
    ec->parameters.push_back(par);
  }
  if (ec->parameters.empty())
    throw r.error("parameters", "at least one parameter", "an empty list");
  std::vector<std::string> names;
  for (const auto& p : ec->parameters) {
    if (std::find(names.begin(), names.end(), p.name) != names.end()) {
      throw r.error("parameters", "distinct parameter names", "\"" + p.name + "\" twice");
    }
    names.push_back(p.name);
  }
  // The bound document must still be a valid scene (e.g. a pointer that adds an unknown key).
  io::parse_scene(ec->scene_doc, ec->scene_file);
}

ObjectiveTerm parse_objective_term(io::JsonReader& t) {
  ObjectiveTerm term;
  term.metric = metric_of(t);
  term.weight = t.number_or("weight", 1.0, -1e9, 1e9);
  term.how = parse_aggregate(t, "mean");
  term.alpha = t.number_or("alpha", 0.2, 1e-6, 1.0);
  t.finish();
  return term;
}

// A multi-objective study's "objectives": [{"name", "terms": [terms as in "objective"]}].
void parse_study_objectives(io::JsonReader& r, EvaluatorConfig* ec) {
  if (r.has("objective")) {
    throw r.error("objective",
                  "no \"objective\" beside \"objectives\" (a multi-objective study lists "
                  "each objective's terms under \"objectives\")",
                  "both");
  }
  r.optional("objective");
  for (io::JsonReader o : r.object_array("objectives")) {
    NamedObjective no;
    no.name = o.string_or("name", "");
    if (no.name.empty()) throw o.error("name", "an objective name", "nothing");
    for (const auto& other : ec->objectives) {
      if (other.name == no.name)
        throw o.error("name", "distinct objective names", "\"" + no.name + "\" twice");
    }
    for (io::JsonReader t : o.object_array("terms")) no.terms.push_back(parse_objective_term(t));
    if (no.terms.empty()) throw o.error("terms", "at least one objective term", "an empty list");
    o.finish();
    ec->objectives.push_back(std::move(no));
  }
  if (ec->objectives.empty())
    throw r.error("objectives", "at least one objective", "an empty list");
}

// Objective terms and constraints, their metrics checked against the study's model.
void parse_study_objective(io::JsonReader& r, const std::string& file, scene::ModelKind model,
                           EvaluatorConfig* ec) {
  if (r.has("objectives")) {
    parse_study_objectives(r, ec);
  } else {
    r.optional("objectives");
    for (io::JsonReader t : r.object_array("objective"))
      ec->objective.push_back(parse_objective_term(t));
    if (ec->objective.empty())
      throw r.error("objective", "at least one objective term", "an empty list");
  }
  if (r.has("constraints")) {
    for (io::JsonReader c : r.object_array("constraints")) {
      ConstraintSpec cs;
      cs.metric = metric_of(c);
      cs.how = parse_aggregate(c, "worst");
      cs.alpha = c.number_or("alpha", 0.2, 1e-6, 1.0);
      cs.has_max = c.has("max");
      cs.has_min = c.has("min");
      if (cs.has_max == cs.has_min)
        throw c.error("max", "exactly one of \"max\" or \"min\"", cs.has_max ? "both" : "neither");
      if (cs.has_max) cs.max = c.number("max");
      if (cs.has_min) cs.min = c.number("min");
      c.optional("max");
      c.optional("min");
      c.finish();
      ec->constraints.push_back(cs);
    }
  } else {
    r.optional("constraints");
  }
  // A metric only the full model reports is an error in a reduced-model study.
  auto check_metric = [&](const std::string& at, const std::string& m) {
    if (is_metric(m, model)) return;
    throw io::InputError(file, at,
                         "a metric the " + std::string(scene::to_string(model)) + " model reports",
                         "\"" + m + "\" (only the pseudo_rigid model reports it)");
  };
  for (size_t i = 0; i < ec->objective.size(); ++i)
    check_metric("/objective/" + std::to_string(i) + "/metric", ec->objective[i].metric);
  for (size_t i = 0; i < ec->objectives.size(); ++i) {
    for (size_t k = 0; k < ec->objectives[i].terms.size(); ++k) {
      check_metric("/objectives/" + std::to_string(i) + "/terms/" + std::to_string(k) + "/metric",
                   ec->objectives[i].terms[k].metric);
    }
  }
  for (size_t i = 0; i < ec->constraints.size(); ++i)
    check_metric("/constraints/" + std::to_string(i) + "/metric", ec->constraints[i].metric);
}

// An OptimizerOptions::validate error ("field: value: rule") as an InputError at
// /optimizer/<field>; a rule "expected ..." becomes what was expected.
io::InputError optimizer_error(const std::string& file, const std::string& err) {
  const std::size_t colon = err.find(": ");
  std::string field = err.substr(0, colon);
  if (field.rfind("ipopt_options", 0) == 0) field.replace(0, 13, "options");  // the JSON key
  const std::string pointer = "/optimizer/" + field;
  const std::size_t rule = colon == std::string::npos ? colon : err.find(": expected ", colon);
  if (rule == std::string::npos)
    return io::InputError(file, pointer, "valid optimizer options", err);
  return io::InputError(file, pointer, err.substr(rule + 11),
                        err.substr(colon + 2, rule - colon - 2));
}

bool is_moo_algorithm(const std::string& name) {
  const auto& names = pareto::moo_algorithm_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// A MooOptions::validate message ("field: value: expected rule") as an InputError: the
// objective count at /objectives (or /objective), the algorithm at /optimizer/algorithm,
// everything else at /optimizer/options/<field>.
io::InputError moo_error(const std::string& file, const std::string& err, bool multi_form) {
  const std::size_t colon = err.find(": ");
  const std::string field = err.substr(0, colon);
  std::string pointer = "/optimizer/options/" + field;
  if (field.rfind("options/", 0) == 0) pointer = "/optimizer/" + field;
  if (field == "algorithm") pointer = "/optimizer/algorithm";
  if (field == "objectives") pointer = multi_form ? "/objectives" : "/objective";
  if (colon == std::string::npos)
    return io::InputError(file, pointer, "valid multi-objective options", err);
  if (field == "objectives") {
    const std::size_t end = err.find(": ", colon + 2);
    return io::InputError(file, pointer,
                          "at least 2 objectives (a multi-objective algorithm needs at least 2)",
                          err.substr(colon + 2, end == std::string::npos ? end : end - colon - 2));
  }
  std::size_t rule = err.find(": expected ", colon);
  std::size_t skip = 11;
  if (rule == std::string::npos) {  // "field: value: rule" with a rule that is no "expected ..."
    rule = err.find(": ", colon + 2);
    skip = 2;
  }
  if (rule == std::string::npos)
    return io::InputError(file, pointer, "valid multi-objective options", err);
  return io::InputError(file, pointer, err.substr(rule + skip),
                        err.substr(colon + 2, rule - colon - 2));
}

// The multi-objective form of "optimizer" (library pagmo, algorithm nsga2 | moead | nspso):
// seed and penalty_weight as for the other libraries, and "options" holding population,
// generations, an optional hypervolume reference point and the algorithm's own options.
void parse_moo_optimizer(io::JsonReader& o, const json& doc, const std::string& file,
                         long objectives, bool multi_form, OptimizerOptions* op,
                         std::optional<pareto::MooOptions>* moo) {
  for (const char* key : {"max_evaluations", "max_time"}) {
    if (o.has(key)) {
      throw o.error(key,
                    "no \"" + std::string(key) +
                        "\" with a multi-objective algorithm (it runs "
                        "options/population x (options/generations + 1) evaluations)",
                    io::describe(doc.at("optimizer").at(key)));
    }
  }
  pareto::MooOptions m;
  m.algorithm = op->algorithm;
  op->seed = static_cast<unsigned long long>(o.integer_or("seed", 1, 0, 9007199254740991L));
  m.seed = op->seed;
  op->penalty_weight = o.number_or("penalty_weight", op->penalty_weight, 1e-300, 1e12);
  if (o.has("options")) {
    const json& opts = doc.at("optimizer").at("options");
    o.optional("options");
    if (!opts.is_object())
      throw o.error("options", "an object of pagmo options", io::describe(opts));
    io::JsonReader x = o.object("options");
    m.population = x.integer_or("population", m.population, 1, 1000000);
    m.generations = x.integer_or("generations", m.generations, 1, 100000000);
    if (x.has("reference")) {
      const Eigen::VectorXd ref = x.vector("reference", static_cast<int>(objectives));
      m.reference.assign(ref.data(), ref.data() + ref.size());
    } else {
      x.optional("reference");
    }
    for (auto it = opts.begin(); it != opts.end(); ++it) {
      if (it.key() == "population" || it.key() == "generations" || it.key() == "reference")
        continue;
      m.options[it.key()] = it.value();
      x.optional(it.key());
    }
    x.finish();
  } else {
    o.optional("options");
  }
  for (const char* key : {"max_evaluations", "max_time"}) o.optional(key);
  o.finish();
  const std::vector<std::string> errors = m.validate(objectives);
  if (!errors.empty()) throw moo_error(file, errors.front(), multi_form);
  *moo = m;
}

void parse_study_optimizer(io::JsonReader o, const json& doc, const std::string& file,
                           const EvaluatorConfig& ec, OptimizerOptions* op,
                           std::optional<pareto::MooOptions>* moo) {
  op->library = o.choice_or("library", "nlopt", {"nlopt", "ipopt", "pagmo"});
  const bool pagmo = op->library == "pagmo";
  op->algorithm = o.string_or("algorithm", op->library == "ipopt" ? "ipopt"
                                           : pagmo                ? "cmaes"
                                                                  : "LN_BOBYQA");
  const bool multi_form = !ec.objectives.empty();
  if (pagmo && is_moo_algorithm(op->algorithm)) {
    const long n = multi_form ? static_cast<long>(ec.objectives.size()) : 1L;
    parse_moo_optimizer(o, doc, file, n, multi_form, op, moo);
    return;
  }
  if (multi_form) {
    std::string names;
    for (const auto& a : pareto::moo_algorithm_names()) names += (names.empty() ? "" : ", ") + a;
    throw o.error("algorithm",
                  "a multi-objective algorithm of library pagmo (" + names +
                      ") for a study with \"objectives\"",
                  op->library + " \"" + op->algorithm + "\"");
  }
  // NLopt's and Ipopt's stopping rules and derivatives mean nothing to pagmo: refuse them
  // rather than ignore them.
  for (const char* key : {"local_algorithm", "ftol_rel", "xtol_rel", "fd_step"}) {
    if (pagmo && o.has(key)) {
      throw o.error(key,
                    "no \"" + std::string(key) +
                        "\" with library pagmo (it takes no local algorithm and no derivatives; "
                        "its tolerances are options/ftol and options/xtol)",
                    io::describe(doc.at("optimizer").at(key)));
    }
  }
  op->local_algorithm = o.string_or("local_algorithm", op->local_algorithm);
  op->max_evaluations = o.integer_or("max_evaluations", op->max_evaluations, 1, 100000000);
  op->max_time = o.number_or("max_time", 0.0, 0.0, 1e9);
  op->ftol_rel = o.number_or("ftol_rel", op->ftol_rel, 0.0, 1.0);
  op->xtol_rel = o.number_or("xtol_rel", op->xtol_rel, 0.0, 1.0);
  op->seed = static_cast<unsigned long long>(o.integer_or("seed", 1, 0, 9007199254740991L));
  op->penalty_weight = o.number_or("penalty_weight", op->penalty_weight, 0.0, 1e12);
  op->fd_step = o.number_or("fd_step", op->fd_step, 1e-12, 0.1);
  if (o.has("options")) {
    const json& opts = doc.at("optimizer").at("options");
    o.optional("options");
    if (!opts.is_object())
      throw o.error("options", pagmo ? "an object of pagmo options" : "an object of Ipopt options",
                    io::describe(opts));
    (pagmo ? op->pagmo_options : op->ipopt_options) = opts;
  } else {
    o.optional("options");
  }
  o.finish();
  std::string err;
  if (!op->validate(&err)) throw optimizer_error(file, err);
}

}  // namespace

Study parse_study(const json& doc, const std::string& file, const std::string& base_dir) {
  Study st;
  st.file = file;
  st.document = doc;
  io::JsonReader r(doc, file, "");
  st.name = r.path_name_or("name", "");  // the default output directory results/<name>
  r.string_or("description", "");
  // The scene: a path (relative to the study file) or an inline object, plus overrides.
  std::string scene_file;
  json scene_doc = read_study_scene(r, doc, file, base_dir, &scene_file);
  apply_study_scene_overrides(r, doc, file, &scene_doc);
  // A study-level "model" runs every scenario in that model, whatever the scene says.
  if (r.has("model")) {
    scene_doc["model"] = r.choice_or("model", "", scene::model_names());
  } else {
    r.optional("model");
  }
  // The scene must be valid as given (its errors name the scene file).
  const scene::Scene scene0 = io::parse_scene(scene_doc, scene_file);
  EvaluatorConfig& ec = st.evaluator;
  const json resolved = io::scene_to_json(scene0);  // (the hash's: without the defaulted)
  json bindable = resolved;  // every number a parameter or a perturbation can name
  io::add_defaulted_settings(&bindable);
  ec.scene_doc = bindable;
  ec.scene_file = scene_file;
  parse_study_parameters(r, scene0, bindable, &ec);

  // Scenarios, and the optional held-out validation set.
  // Robot perturbations are checked against the scene at the parameters' starts.
  PerturbationContext robot{&ec.scene_doc, scene0.model, io::unused_settings(scene0), scene_file};
  parse_scenario_set(r.object("scenarios"), robot, ec.scenarios);
  if (r.has("validation")) {
    ScenarioSet v;
    parse_scenario_set(r.object("validation"), robot, v);
    st.validation = v;
  } else {
    r.optional("validation");
  }
  parse_study_objective(r, file, scene0.model, &ec);
  ec.stability = r.boolean_or("stability", true);
  if (ec.stability && scene::is_full_model(scene0.model) && !scene0.pseudo_rigid.actuators) {
    throw r.error("stability",
                  "false for passive legs: the full model's stride-map fit needs a controlled gait",
                  "true, with /pseudo_rigid/actuators false");
  }
  ec.fall_penalty = r.positive_or("fall_penalty", 1.0);
  parse_study_optimizer(r.object("optimizer"), doc, file, ec, &st.optimizer, &st.moo);
  st.output_dir = r.string_or("output", "results/" + st.name);
  r.finish();
  st.hash = fnv1a_hex(doc.dump() + "\n" + resolved.dump());
  return st;
}

Study load_study(const std::string& path, const std::vector<std::string>& overrides) {
  json doc = io::read_json_file(path);
  for (const auto& o : overrides) io::apply_override(doc, o);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_study(doc, path, dir.empty() ? "." : dir);
}

}  // namespace pronk::optimize
