#include "optimize/design_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <set>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/table.hpp"
#include "optimize/design_reader_detail.hpp"
#include "optimize/parameters.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace design_detail {

void require(const io::JsonReader& r, const std::string& key) {
  if (!r.has(key)) throw r.error(key, "a recorded value", "nothing");
}

std::string required_string(io::JsonReader& r, const std::string& key) {
  require(r, key);
  return r.string_or(key, "");
}

bool required_bool(io::JsonReader& r, const std::string& key) {
  require(r, key);
  return r.boolean_or(key, false);
}

MetricMap read_numbers(io::JsonReader& parent, const json& node, const std::string& key,
                       const std::function<bool(const std::string&)>& allowed,
                       const std::string& what) {
  require(parent, key);
  io::JsonReader r = parent.object(key);
  MetricMap out;
  for (auto it = node.at(key).begin(); it != node.at(key).end(); ++it) {
    if (!allowed(it.key())) {
      throw r.error(it.key(), what, "\"" + it.key() + "\"");
    }
    out[it.key()] = r.number(it.key());
  }
  r.finish();
  return out;
}

}  // namespace design_detail

namespace {

using namespace design_detail;

// A number the design derives from others (parameter values, the scene, a cost from its
// metrics) may differ from its recomputation by this much: the round-off of the mapping on
// another build. Any edit that means something is far larger.
constexpr double kDerivedRtol = 1e-12;

bool close(double a, double b) {
  return std::abs(a - b) <= kDerivedRtol * std::max(std::abs(a), std::abs(b)) + 1e-300;
}

std::string num(double x) { return io::exact_number(x); }

// Membership in `names` as a predicate.
std::function<bool(const std::string&)> in(const std::set<std::string>& names) {
  return [&names](const std::string& k) { return names.count(k) > 0; };
}

std::string aggregate_key(Aggregate how, const std::string& metric) {
  return std::string(to_string(how)) + "(" + metric + ")";
}

// Every name an evaluation of this study may report: the model's metrics and the
// objective's and constraints' aggregates.
std::set<std::string> recorded_names(const EvaluatorConfig& cfg, scene::ModelKind model) {
  std::set<std::string> names(metric_names(model).begin(), metric_names(model).end());
  for (const auto& t : cfg.objective) names.insert(aggregate_key(t.how, t.metric));
  for (const auto& c : cfg.constraints) names.insert(aggregate_key(c.how, c.metric));
  return names;
}

// The recorded cost is the objective of the recorded metrics (a failed evaluation records
// the failure cost and no metrics to check it by).
void check_cost(const RecordedSet& set, const EvaluatorConfig& cfg, const std::string& path,
                const std::string& at, const std::string& cost_key,
                const std::string& metrics_key) {
  if (set.metrics.empty() || set.cost == cfg.failure_cost) return;
  double cost = 0.0;
  for (const auto& t : cfg.objective) {
    const std::string key = aggregate_key(t.how, t.metric);
    const auto it = set.metrics.find(key);
    if (it == set.metrics.end()) {
      throw io::InputError(path, at + "/" + metrics_key + "/" + io::pointer_escape(key),
                           "a recorded value (an aggregate of the study's objective)", "nothing");
    }
    cost += t.weight * it->second;
  }
  if (!close(cost, set.cost)) {
    throw io::InputError(path, at + "/" + cost_key,
                         "the cost its metrics give through the study's objective, " + num(cost),
                         num(set.cost));
  }
}

// The decisions a set's trials record agree with the set's scenarios and its metrics.
std::vector<TrialDecision> read_trials(const json& node, const std::string& path,
                                       const std::string& at, const ScenarioSet& set,
                                       const MetricMap& metrics) {
  const size_t n = set.scenarios.size();
  if (!node.is_array() || node.size() != n) {
    throw io::InputError(path, at, "an array of " + run::count_text(static_cast<long>(n), "trial"),
                         io::describe(node));
  }
  std::vector<TrialDecision> out;
  for (size_t i = 0; i < n; ++i) {
    io::JsonReader r(node[i], path, at + "/" + std::to_string(i));
    TrialDecision t;
    t.name = required_string(r, "name");
    if (t.name != set.scenarios[i].name) {
      throw r.error("name", "\"" + set.scenarios[i].name + "\" (the study's scenario)",
                    "\"" + t.name + "\"");
    }
    require(r, "status");
    t.status = r.choice_or("status", "", {"completed", "fell", "diverged"});
    t.stabilized = required_bool(r, "stabilized");
    t.apex_held = required_bool(r, "apex_held");
    r.finish();
    out.push_back(t);
  }
  // Each decision's fraction is the recorded mean of its 0/1 metric (exact: k / n).
  auto check = [&](const char* metric, auto&& decided) {
    const auto it = metrics.find(metric);
    if (it == metrics.end() || n == 0) return;
    std::vector<double> v;
    for (const auto& t : out) v.push_back(decided(t) ? 1.0 : 0.0);
    const double mean = aggregate(v, Aggregate::kMean, 0);
    if (mean != it->second) {
      throw io::InputError(path, at,
                           "trials whose " + std::string(metric) + " fraction is " +
                               num(it->second) + " (the recorded metric)",
                           num(mean));
    }
  };
  check("stabilized", [](const TrialDecision& t) { return t.stabilized; });
  check("apex_held", [](const TrialDecision& t) { return t.apex_held; });
  check("fell", [](const TrialDecision& t) { return t.status != "completed"; });
  return out;
}

// The tolerances of one set: a cost and every metric the set records, each >= 0.
void read_tolerance(io::JsonReader& parent, const json& node, RecordedSet* set) {
  io::JsonReader r = parent.object("tolerance");
  set->cost_tolerance = r.number("cost", 0.0);
  std::set<std::string> names;
  for (const auto& [k, v] : set->metrics) names.insert(k);
  set->tolerances =
      read_numbers(r, node.at("tolerance"), "metrics", in(names), "a metric the design records");
  for (const auto& [k, v] : set->metrics) {
    if (set->tolerances.count(k) == 0) {
      throw io::InputError(r.file(), r.pointer_of("metrics") + "/" + io::pointer_escape(k),
                           "a tolerance", "nothing");
    }
  }
  for (const auto& [k, v] : set->tolerances) {
    if (v < 0) {
      throw io::InputError(r.file(), r.pointer_of("metrics") + "/" + io::pointer_escape(k),
                           "a tolerance >= 0", num(v));
    }
  }
  r.finish();
  require(parent, "fragile_trials");
  const long n = set->trials ? static_cast<long>(set->trials->size()) : 0;
  set->fragile = parent.integer_array_or("fragile_trials", 0, std::max(0L, n - 1));
}

// The "reproduction" record: how the tolerances were measured, and each set's.
void read_reproduction(io::JsonReader& top, const json& design, RecordedDesign* d) {
  require(top, "reproduction");
  io::JsonReader r = top.object("reproduction");
  const json& node = design.at("reproduction");
  require(r, "method");
  r.choice_or("method", "", {"perturbation"});
  require(r, "perturbations");
  r.integer_or("perturbations", 0, 1, 1000);
  r.number("step", 0.0, 1e-3);
  r.number("safety_factor", 1.0, 1e3);
  r.number("wall_time_s", 0.0);
  read_tolerance(r, node, &d->scenarios);
  require(r, "validation");
  if (d->validation) {
    io::JsonReader v = r.object("validation");
    read_tolerance(v, node.at("validation"), &*d->validation);
    v.finish();
  } else if (!node.at("validation").is_null()) {
    throw r.error("validation", "null (the study has no validation set)",
                  io::describe(node.at("validation")));
  } else {
    r.optional("validation");
  }
  r.finish();
}

// The cost and metrics of the tuned and the initial design on one set, at `at` ("" for the
// study's scenarios, "/validation"), checked against each other and the objective.
RecordedSet read_set(io::JsonReader& r, const json& node, const std::string& at,
                     const EvaluatorConfig& cfg, const std::set<std::string>& names) {
  const std::string what = "a metric of the study's model or an aggregate of its objective";
  RecordedSet set;
  require(r, "cost");
  set.cost = r.number("cost");
  set.metrics = read_numbers(r, node, "metrics", in(names), what);
  RecordedSet initial;
  require(r, "initial_cost");
  initial.cost = r.number("initial_cost");
  initial.metrics = read_numbers(r, node, "initial_metrics", in(names), what);
  check_cost(set, cfg, r.file(), at, "cost", "metrics");
  check_cost(initial, cfg, r.file(), at, "initial_cost", "initial_metrics");
  // Both designs were evaluated by the same study: the same names (unless one failed).
  if (!set.metrics.empty() && !initial.metrics.empty()) {
    for (const auto& m : {set.metrics, initial.metrics}) {
      for (const auto& [k, v] : m) {
        if (!set.metrics.count(k) || !initial.metrics.count(k)) {
          throw io::InputError(r.file(),
                               at + (set.metrics.count(k) ? "/initial_metrics/" : "/metrics/") +
                                   io::pointer_escape(k),
                               "a recorded value (the other design records it)", "nothing");
        }
      }
    }
  }
  return set;
}

// The recorded constraint values are the constraints of the recorded metrics.
void check_constraints(io::JsonReader& r, const json& design, const EvaluatorConfig& cfg,
                       const RecordedSet& set) {
  require(r, "constraints");
  const size_t n = cfg.constraints.size();
  const Eigen::VectorXd g = r.vector("constraints", static_cast<int>(n));
  required_bool(r, "feasible");
  if (set.metrics.empty() || set.cost == cfg.failure_cost) return;
  for (size_t c = 0; c < n; ++c) {
    const ConstraintSpec& spec = cfg.constraints[c];
    const auto it = set.metrics.find(aggregate_key(spec.how, spec.metric));
    if (it == set.metrics.end()) continue;  // check_cost's names are required; these follow
    const double expected = spec.has_max ? it->second - spec.max : spec.min - it->second;
    if (!close(expected, g[static_cast<long>(c)])) {
      throw io::InputError(r.file(), "/constraints/" + std::to_string(c),
                           "the value the recorded metrics give, " + num(expected),
                           num(design.at("constraints")[c].get<double>()));
    }
  }
}

// The optimizer coordinates: one per parameter, each in [0, 1].
std::vector<double> read_unit(io::JsonReader& r, int dimension) {
  require(r, "unit");
  const Eigen::VectorXd u = r.vector("unit", dimension, 0.0, 1.0);
  return std::vector<double>(u.data(), u.data() + u.size());
}

// The parameter values and the tuned scene are the unit mapped through the study.
void check_parameters_and_scene(io::JsonReader& r, const json& design, const RecordedDesign& d) {
  const EvaluatorConfig& cfg = d.study.evaluator;
  const std::vector<double> values = physical_values(cfg.parameters, d.unit);
  require(r, "parameters");
  io::JsonReader p = r.object("parameters");
  for (size_t i = 0; i < cfg.parameters.size(); ++i) {
    const std::string& name = cfg.parameters[i].name;
    if (!p.has(name)) throw p.error(name, "a recorded value (a parameter of the study)", "nothing");
    const double v = p.number(name);
    if (!close(v, values[i])) {
      throw p.error(name, "the value the design's unit gives, " + num(values[i]), num(v));
    }
  }
  p.finish();
  require(r, "scene");
  r.optional("scene");
  const json expected = io::scene_to_json(
      io::parse_scene(bind_parameters(cfg.scene_doc, cfg.parameters, d.unit), cfg.scene_file));
  // Settings the scene format gained after the design was written are not in it.
  const std::string at =
      first_json_difference(expected, design.at("scene"), kDerivedRtol, "/scene", true);
  if (!at.empty()) {
    const json::json_pointer ptr(at.substr(6).empty() ? "" : at.substr(6));
    auto text = [&](const json& j) {
      return j.contains(ptr) ? io::describe(j.at(ptr)) : "nothing";
    };
    throw io::InputError(r.file(), at,
                         "the scene the design's unit gives through the study, " + text(expected),
                         text(design.at("scene")));
  }
}

// The optimizer's report and the stability analysis: their fields and types.
void check_run_records(io::JsonReader& r, const Study& st) {
  require(r, "optimizer");
  io::JsonReader o = r.object("optimizer");
  const std::string library = required_string(o, "library");
  if (library != st.optimizer.library) {
    throw o.error("library", "\"" + st.optimizer.library + "\" (the study's)",
                  "\"" + library + "\"");
  }
  for (const char* k : {"algorithm", "status", "message"}) required_string(o, k);
  for (const char* k : {"evaluations", "failed_evaluations"}) {
    require(o, k);
    o.integer_or(k, 0, 0, 9007199254740991L);
  }
  o.finish();
  if (!r.has("stability")) {  // designs from before pronk recorded it
    r.optional("stability");
    return;
  }
  io::JsonReader s = r.object("stability");
  required_string(s, "method");
  required_bool(s, "ok");
  required_string(s, "reason");
  s.finish();
}

// Who recorded the design (the build identity) and of which study: names, hashes, seed.
void read_identity(io::JsonReader& r, RecordedDesign* d) {
  const Study& st = d->study;
  const std::string name = required_string(r, "study");
  if (name != st.name) {
    throw r.error("study", "\"" + st.name + "\" (the name in /study_document)", "\"" + name + "\"");
  }
  const std::string hash = required_string(r, "study_hash");
  if (hash.size() != 16 || hash.find_first_not_of("0123456789abcdef") != std::string::npos) {
    throw r.error("study_hash", "16 hex digits", "\"" + hash + "\"");
  }
  if (r.has("study_document_hash")) {
    const std::string doc_hash = r.string_or("study_document_hash", "");
    if (doc_hash != st.hash) {
      throw r.error("study_document_hash",
                    "\"" + st.hash + "\" (the hash of /study_document as recorded)",
                    "\"" + doc_hash + "\"");
    }
  } else {
    r.optional("study_document_hash");
  }
  required_string(r, "version");
  d->commit = required_string(r, "commit");
  d->compiler = required_string(r, "compiler");
  d->build_flags = r.string_or("build_flags", "");
  require(r, "seed");
  const long seed = r.integer_or("seed", 0, 0, 9007199254740991L);
  if (static_cast<unsigned long long>(seed) != st.optimizer.seed) {
    throw r.error("seed", std::to_string(st.optimizer.seed) + " (the study's optimizer seed)",
                  std::to_string(seed));
  }
  require(r, "threads");
  r.integer_or("threads", 1, 1, 1L << 20);
  r.number("wall_time_s", 0.0);
  const std::string scene_model = st.evaluator.scene_doc.value("model", std::string());
  const std::string model = r.string_or("model", scene_model);  // older designs lack it
  if (model != scene_model) {
    throw r.error("model", "\"" + scene_model + "\" (the model of the study's scene)",
                  "\"" + model + "\"");
  }
  check_run_records(r, st);
}

// The validation record: an object exactly when the study has a validation set.
std::optional<RecordedSet> read_validation(io::JsonReader& r, const json& design, const Study& st,
                                           const std::set<std::string>& names) {
  require(r, "validation");
  const json& v = design.at("validation");
  if (!st.validation) {
    if (!v.is_null())
      throw r.error("validation", "null (the study has no validation set)", io::describe(v));
    r.optional("validation");
    return std::nullopt;
  }
  const size_t n = st.validation->scenarios.size();
  if (!v.is_object()) {
    throw r.error("validation",
                  "the validation record (the study has a validation set of " + std::to_string(n) +
                      " trials)",
                  io::describe(v));
  }
  io::JsonReader vr = r.object("validation");
  require(vr, "scenarios");
  const long count = vr.integer_or("scenarios", 0, 0, 1L << 40);
  if (static_cast<size_t>(count) != n) {
    throw vr.error("scenarios", std::to_string(n) + " (the study's validation set)",
                   std::to_string(count));
  }
  RecordedSet set = read_set(vr, v, "/validation", st.evaluator, names);
  if (vr.has("trials")) {
    set.trials =
        read_trials(v.at("trials"), r.file(), "/validation/trials", *st.validation, set.metrics);
  }
  vr.optional("trials");
  vr.finish();
  return set;
}

}  // namespace

RecordedDesign read_design(const json& design, const std::string& path) {
  if (!io::holds(design, "type", "pronk_design")) {
    throw io::InputError(
        path, "/type", "\"pronk_design\" (a design.json of pronk optimize)",
        design.is_object() && design.contains("type") ? io::describe(design["type"]) : "nothing");
  }
  io::JsonReader r(design, path, "");
  r.optional("type");
  require(r, "study_document");
  r.optional("study_document");
  const std::string dir = std::filesystem::path(path).parent_path().string();
  RecordedDesign d;
  d.study =
      parse_study(design.at("study_document"), path + "#/study_document", dir.empty() ? "." : dir);
  const EvaluatorConfig& cfg = d.study.evaluator;
  read_identity(r, &d);
  d.unit = read_unit(r, static_cast<int>(cfg.parameters.size()));
  check_parameters_and_scene(r, design, d);
  const std::set<std::string> names =
      recorded_names(cfg, io::parse_scene(cfg.scene_doc, cfg.scene_file).model);
  d.scenarios = read_set(r, design, "", cfg, names);
  check_constraints(r, design, cfg, d.scenarios);
  d.validation = read_validation(r, design, d.study, names);
  // Per-trial decisions and tolerances: both (a design pronk writes now) or neither (one
  // recorded before pronk recorded them).
  const bool trials = r.has("trials");
  if (trials != r.has("reproduction")) {
    throw r.error(trials ? "reproduction" : "trials",
                  std::string("a recorded value (the design records ") +
                      (trials ? "per-trial decisions" : "tolerances") + "; both or neither)",
                  "nothing");
  }
  if (d.validation && d.validation->trials.has_value() != trials) {
    throw io::InputError(path, "/validation/trials",
                         trials ? "the validation trials (the design records /trials)"
                                : "nothing (the design records no /trials)",
                         trials ? "nothing" : "an array");
  }
  if (trials) {
    d.scenarios.trials =
        read_trials(design.at("trials"), path, "/trials", cfg.scenarios, d.scenarios.metrics);
    r.optional("trials");
    read_reproduction(r, design, &d);
  } else {
    r.optional("trials");
    r.optional("reproduction");
  }
  if (r.has("staged_study")) {
    check_staged_records(r, design);
  } else {
    for (const char* k : {"stages", "fidelity_gap", "cross_evaluation", "staged_study_document"}) {
      if (r.has(k))
        throw r.error(k, "nothing (only a staged study's design, with /staged_study)", "a value");
    }
  }
  r.finish();
  return d;
}

std::string first_json_difference(const json& a, const json& b, double rtol,
                                  const std::string& pointer, bool b_may_omit) {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    return std::abs(x - y) <= rtol * std::max(std::abs(x), std::abs(y)) + 1e-300 ? "" : pointer;
  }
  if (a.type() != b.type()) return pointer;
  if (a.is_object()) {
    for (auto it = a.begin(); it != a.end(); ++it) {
      const std::string p = pointer + "/" + io::pointer_escape(it.key());
      if (!b.contains(it.key())) {
        if (b_may_omit) continue;
        return p;
      }
      const std::string d = first_json_difference(it.value(), b.at(it.key()), rtol, p, b_may_omit);
      if (!d.empty()) return d;
    }
    for (auto it = b.begin(); it != b.end(); ++it) {
      if (!a.contains(it.key())) return pointer + "/" + io::pointer_escape(it.key());
    }
    return "";
  }
  if (a.is_array()) {
    if (a.size() != b.size()) return pointer;
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string d =
          first_json_difference(a[i], b[i], rtol, pointer + "/" + std::to_string(i), b_may_omit);
      if (!d.empty()) return d;
    }
    return "";
  }
  return a == b ? "" : pointer;
}

}  // namespace pronk::optimize
