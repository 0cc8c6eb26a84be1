#include "optimize/moo_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/run_output.hpp"
#include "optimize/journal.hpp"
#include "optimize/output_lock.hpp"
#include "optimize/progress.hpp"
#include "optimize/reproduction_record.hpp"
#include "optimize/study_history.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace {

constexpr double kFeasibilityTolerance = 1e-8;  // OptimizerOptions::feasibility_tolerance

/// What the front needs of one evaluation of the run.
struct Outcome {
  bool ok = true;
  bool feasible = false;
  std::vector<double> objectives;  ///< unpenalized
};

Outcome outcome_of(bool ok, const std::vector<double>& objectives,
                   const std::vector<double>& constraints) {
  Outcome o;
  o.ok = ok;
  o.objectives = objectives;
  o.feasible = ok && std::all_of(constraints.begin(), constraints.end(),
                                 [](double g) { return g <= kFeasibilityTolerance; });
  return o;
}

/// The objective vector the driver sees: every objective plus the constraint penalty.
std::vector<double> penalized(const std::vector<double>& objectives,
                              const std::vector<double>& constraints, double weight) {
  const double p = constraint_penalty(constraints, weight);
  std::vector<double> f = objectives;
  for (double& v : f) v += p;
  return f;
}

struct StopRequested {};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

json metrics_of(const Evaluation& e) {
  json m = json::object();
  for (const auto& [k, v] : e.aggregated) m[k] = v;
  return m;
}

double metric_or(const Evaluation& e, const std::string& k, double fallback) {
  const auto it = e.aggregated.find(k);
  return it == e.aggregated.end() ? fallback : it->second;
}

std::vector<std::string> parameter_names(const EvaluatorConfig& ev) {
  std::vector<std::string> n;
  for (const auto& p : ev.parameters) n.push_back(p.name);
  return n;
}

std::vector<std::string> objective_names(const Study& st) {
  std::vector<std::string> n;
  for (const auto& o : st.evaluator.objectives) n.push_back(o.name);
  return n;
}

std::string summary_markdown(const Study& st, const MooStudyOutcome& o) {
  std::ostringstream md;
  md << "# Study `" << st.name << "` (multi-objective)\n\n";
  md << "Optimizer: pagmo " << st.moo->algorithm << ", population " << st.moo->population << ", "
     << st.moo->generations << " generations after the first population, seed " << st.moo->seed
     << ": " << o.evaluations << " evaluations (" << o.replayed << " replayed from the journal), "
     << o.feasible << " feasible, " << o.failed << " failed, wall time " << o.wall_time
     << " s.\n\n";
  md << "Front: " << o.front.size() << " feasible non-dominated designs, hypervolume "
     << o.front_hypervolume << " against the reference point (";
  for (size_t j = 0; j < o.result.reference.size(); ++j)
    md << (j ? ", " : "") << o.result.reference[j];
  md << "); knee: front index " << o.knee << ".\n\n| front index | evaluation |";
  for (const auto& n : objective_names(st)) md << " " << n << " |";
  if (st.validation) md << " validation stabilized | validation fell |";
  md << "\n|---|---|";
  for (size_t j = 0; j < st.evaluator.objectives.size(); ++j) md << "---|";
  if (st.validation) md << "---|---|";
  md << "\n";
  for (size_t k = 0; k < o.front.size(); ++k) {
    const auto& d = o.front[k];
    md << "| " << k << (static_cast<long>(k) == o.knee ? " (knee)" : "") << " | " << d.evaluation
       << " |";
    for (double v : d.scenarios.objectives) md << " " << v << " |";
    if (d.validation) {
      md << " " << metric_or(*d.validation, "stabilized", 0.0) << " | "
         << metric_or(*d.validation, "fell", 0.0) << " |";
    }
    md << "\n";
  }
  md << "\nFiles: `pareto.csv`, `pareto.json` (reproduce a design with `pronk reproduce "
     << o.out_dir << "/pareto.json --front-index K`), `journal.jsonl`, `timings.csv`.\n";
  return md.str();
}

// tolerance_json's metrics, plus the objectives and constraint values, each kSafetyFactor
// times the largest change a perturbation made to it.
json front_tolerance(const Evaluation& reference, const std::vector<Evaluation>& perturbed) {
  json t = tolerance_json(reference, perturbed);
  t.erase("cost");  // a multi-objective study's cost is 0
  auto spread = [&](const std::vector<double>& ref, auto member) {
    std::vector<double> out(ref.size(), 0.0);
    for (const Evaluation& e : perturbed) {
      const std::vector<double>& v = e.*member;
      for (size_t j = 0; j < ref.size() && j < v.size(); ++j)
        out[j] = std::max(out[j], std::abs(v[j] - ref[j]));
    }
    for (double& x : out) x *= kSafetyFactor;
    return out;
  };
  t["objectives"] = spread(reference.objectives, &Evaluation::objectives);
  t["constraints"] = spread(reference.constraints, &Evaluation::constraints);
  return t;
}

}  // namespace

double constraint_penalty(const std::vector<double>& constraints, double weight) {
  double s = 0.0;
  for (double g : constraints) s += g > 0.0 ? g * g : 0.0;
  return weight * s;
}

MooStudyOutcome run_moo_study(const Study& st, const StudyRunOptions& opt) {
  if (!st.moo) throw std::invalid_argument("run_moo_study: not a multi-objective study");
  const double t0 = monotonic_seconds();
  MooStudyOutcome o;
  o.out_dir = opt.out_dir.empty() ? st.output_dir : opt.out_dir;
  io::make_directories(o.out_dir);
  const OutputLock lock(o.out_dir, "pronk optimize");
  const std::string journal_path = o.out_dir + "/journal.jsonl";

  EvaluatorConfig cfg = st.evaluator;
  cfg.threads = opt.threads;
  cfg.farm = opt.farm;
  const Evaluator evaluator(cfg);
  const auto nobj = static_cast<long>(cfg.objectives.size());
  const double weight = st.optimizer.penalty_weight;

  JournalContents previous = resumable_journal(journal_path, st, evaluator, opt, &o.verified);
  const long recorded = static_cast<long>(previous.records.size());
  std::vector<Outcome> outcomes;
  std::vector<pareto::MooEvaluation> replay;
  for (const JournalRecord& rec : previous.records) {
    if (static_cast<long>(rec.objectives.size()) != nobj) {
      throw io::InputError(journal_path,
                           "line " + std::to_string(rec.line_number) + " /objectives",
                           std::to_string(nobj) + " objective values (this study's)",
                           rec.line.contains("objectives") ? rec.line.at("objectives").dump()
                                                           : "nothing");
    }
    replay.push_back({rec.x, penalized(rec.objectives, rec.result.constraints, weight)});
    outcomes.push_back(outcome_of(rec.result.ok, rec.objectives, rec.result.constraints));
  }
  TimingsFile timings(o.out_dir, recorded > 0 ? &previous : nullptr);
  JournalWriter journal(journal_path, journal_header(st, evaluator),
                        recorded > 0 ? prepare_for_append(journal_path, previous.end) : "");
  const long total = st.moo->population * (st.moo->generations + 1);
  Progress progress(opt.progress, st.name + ": evaluation", total, recorded);
  const std::vector<std::string> names = evaluator.variable_names();
  long next = recorded;

  const pareto::BatchFunction batch = [&](const std::vector<pareto::Point>& xs) {
    if (opt.stop_flag && opt.stop_flag->load()) throw StopRequested{};
    std::vector<Evaluation> evs = evaluator.evaluate_full_batch(xs);
    std::vector<std::vector<double>> out;
    out.reserve(evs.size());
    for (const Evaluation& e : evs) {
      timings.write(next, e);  // first: a kill between the two leaves a spare line
      journal.append(journal_record(next, "objective", e, names));
      ++next;
      outcomes.push_back(outcome_of(e.ok, e.objectives, e.constraints));
      out.push_back(penalized(e.objectives, e.constraints, weight));
    }
    progress.update(next);
    return out;
  };
  const std::vector<double> lower(names.size(), 0.0), upper(names.size(), 1.0);
  // The study's start (its parameters' initial values) is the first population's first
  // member: a design known to work is on the first front, the rest is drawn from the seed.
  pareto::MooOptions moo = *st.moo;
  moo.initial_points = {evaluator.initial_point()};
  try {
    o.result = pareto::run(batch, lower, upper, nobj, moo, nullptr, replay);
  } catch (const StopRequested&) {
    progress.finish();
    o.stopped = true;
    o.evaluations = next;
    o.replayed = std::min(recorded, next);
    o.wall_time = monotonic_seconds() - t0;
    return o;
  } catch (const std::invalid_argument& e) {
    // The driver refuses a record that is not the point it asks for: a journal of another run.
    if (std::string(e.what()).rfind("resume:", 0) == 0)
      throw io::InputError(journal_path, "", "the journal of this study's run", e.what());
    throw std::runtime_error(std::string("multi-objective driver: ") + e.what());
  }
  progress.finish();
  journal.sync();
  o.evaluations = static_cast<long>(o.result.evaluations.size());
  o.replayed = o.result.recorded_answers;
  if (static_cast<long>(outcomes.size()) != o.evaluations)
    throw std::logic_error("run_moo_study: evaluations and outcomes out of step");

  // The reported front: the non-dominated feasible designs, unpenalized objectives.
  std::vector<std::size_t> feasible;
  std::vector<pareto::Objectives> points;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    if (!outcomes[i].ok) ++o.failed;
    if (!outcomes[i].feasible) continue;
    feasible.push_back(i);
    points.push_back(outcomes[i].objectives);
  }
  o.feasible = static_cast<long>(feasible.size());
  std::vector<pareto::Point> xs;
  std::vector<pareto::Objectives> front_f;
  for (const std::size_t k : pareto::non_dominated(points)) {
    FrontDesign d;
    d.evaluation = static_cast<long>(feasible[k]);
    o.front.push_back(d);
    xs.push_back(o.result.evaluations[feasible[k]].x);
    front_f.push_back(points[k]);
  }
  o.knee = pareto::knee(front_f);
  o.front_hypervolume = front_f.empty() ? 0.0 : pareto::hypervolume(front_f, o.result.reference);

  // Each front design in full (deterministic: the recorded numbers), and on the validation set.
  std::vector<Evaluation> full = evaluator.evaluate_full_batch(xs);
  for (std::size_t k = 0; k < full.size(); ++k) {
    if (full[k].objectives != front_f[k])
      throw std::logic_error("run_moo_study: a front design evaluated again gave other objectives");
    o.front[k].scenarios = std::move(full[k]);
  }
  std::optional<Evaluator> val;
  if (st.validation) {
    val.emplace(validation_evaluator(st, opt.threads, opt.farm));
    std::vector<Evaluation> v = val->evaluate_full_batch(xs);
    for (std::size_t k = 0; k < v.size(); ++k) o.front[k].validation = std::move(v[k]);
  }
  o.wall_time = monotonic_seconds() - t0;
  // Each front design's perturbation run, all designs' points in one batch per set (timed
  // apart from the study's wall time, as design.json's is).
  std::vector<pareto::Point> moved;
  for (const auto& x : xs)
    for (int k = 0; k < kPerturbations; ++k) moved.push_back(perturbed_unit(x, k));
  const std::vector<Evaluation> moved_s = evaluator.evaluate_full_batch(moved);
  std::vector<Evaluation> moved_v;
  if (val) moved_v = val->evaluate_full_batch(moved);
  for (std::size_t k = 0; k < o.front.size(); ++k) {
    auto slice = [&](const std::vector<Evaluation>& all) {
      return std::vector<Evaluation>(all.begin() + static_cast<long>(k) * kPerturbations,
                                     all.begin() + static_cast<long>(k + 1) * kPerturbations);
    };
    FrontDesign& d = o.front[k];
    d.reproduction = {{"method", "perturbation"},
                      {"perturbations", kPerturbations},
                      {"step", kPerturbationStep},
                      {"safety_factor", kSafetyFactor},
                      {"tolerance", front_tolerance(d.scenarios, slice(moved_s))},
                      {"fragile_trials", fragile_trials(d.scenarios, slice(moved_s))},
                      {"validation", nullptr}};
    if (d.validation) {
      d.reproduction["validation"] = {
          {"tolerance", front_tolerance(*d.validation, slice(moved_v))},
          {"fragile_trials", fragile_trials(*d.validation, slice(moved_v))}};
    }
  }

  io::write_file_atomic(o.out_dir + "/pareto.csv", pareto_csv(st, o));
  io::write_file_atomic(o.out_dir + "/pareto.json",
                        io::dump_checked(pareto_document(st, o, opt.threads)));
  io::write_file_atomic(o.out_dir + "/summary.md", summary_markdown(st, o));
  // Each front design's playback on the first scenario (front/<k>/, the report page's).
  for (std::size_t k = 0; k < xs.size(); ++k) {
    write_design_run(o.out_dir + "/front/" + std::to_string(k), evaluator, xs[k]);
  }
  return o;
}

std::string pareto_csv(const Study& st, const MooStudyOutcome& o) {
  std::ostringstream csv;
  const auto& ev = st.evaluator;
  csv << "front_index,evaluation";
  for (const auto& p : ev.parameters) csv << "," << p.name;
  for (const auto& n : objective_names(st)) csv << "," << n;
  for (size_t c = 0; c < ev.constraints.size(); ++c) csv << ",g" << c;
  csv << ",knee,validation_stabilized,validation_fell\n";
  for (size_t k = 0; k < o.front.size(); ++k) {
    const FrontDesign& d = o.front[k];
    csv << k << "," << d.evaluation;
    for (double v : d.scenarios.values) csv << "," << number(v);
    for (double v : d.scenarios.objectives) csv << "," << number(v);
    for (double g : d.scenarios.constraints) csv << "," << number(g);
    csv << "," << (static_cast<long>(k) == o.knee ? 1 : 0);
    if (d.validation) {
      csv << "," << number(metric_or(*d.validation, "stabilized", 0.0)) << ","
          << number(metric_or(*d.validation, "fell", 0.0));
    } else {
      csv << ",,";
    }
    csv << "\n";
  }
  return csv.str();
}

json pareto_document(const Study& st, const MooStudyOutcome& o, int threads) {
  const auto& ev = st.evaluator;
  json study = st.document;  // the scene inlined: reproducible from this file alone
  study["scene"] = ev.scene_doc;
  study.erase("scene_overrides");
  study.erase("output");
  json constraints = json::array();
  for (const auto& c : ev.constraints) constraints.push_back(c.label());
  json front = json::array();
  for (size_t k = 0; k < o.front.size(); ++k) {
    const FrontDesign& d = o.front[k];
    json values = json::object(), objectives = json::object();
    for (size_t i = 0; i < ev.parameters.size(); ++i)
      values[ev.parameters[i].name] = d.scenarios.values[i];
    for (size_t j = 0; j < ev.objectives.size(); ++j)
      objectives[ev.objectives[j].name] = d.scenarios.objectives[j];
    json validation = nullptr;
    if (d.validation) {
      validation = {{"scenarios", st.validation->scenarios.size()},
                    {"stabilized", metric_or(*d.validation, "stabilized", 0.0)},
                    {"fell", metric_or(*d.validation, "fell", 0.0)},
                    {"objectives", d.validation->objectives},
                    {"constraints", d.validation->constraints},
                    {"metrics", metrics_of(*d.validation)},
                    {"trials", to_json(trial_decisions(*d.validation))}};
    }
    front.push_back({{"index", k},
                     {"evaluation", d.evaluation},
                     {"unit", d.scenarios.unit},
                     {"parameters", values},
                     {"objectives", objectives},
                     {"constraints", d.scenarios.constraints},
                     {"metrics", metrics_of(d.scenarios)},
                     {"trials", to_json(trial_decisions(d.scenarios))},
                     {"validation", validation},
                     {"reproduction", d.reproduction}});
  }
  return {{"type", "pronk_pareto"},
          {"study", st.name},
          {"study_hash", st.hash},
          {"version", pronk::version()},
          {"commit", pronk::git_commit()},
          {"compiler", compiler_id()},
          {"build_flags", pronk::build_flags()},
          {"seed", st.optimizer.seed},
          {"threads", threads},
          {"wall_time_s", o.wall_time},
          {"optimizer",
           {{"library", "pagmo"},
            {"algorithm", st.moo->algorithm},
            {"population", st.moo->population},
            {"generations", st.moo->generations},
            {"seed", st.moo->seed},
            {"options", st.moo->options},
            {"penalty_weight", st.optimizer.penalty_weight},
            {"evaluations", o.evaluations},
            {"batch_calls", o.result.batch_calls}}},
          {"objective_names", objective_names(st)},
          {"parameter_names", parameter_names(ev)},
          {"constraint_names", constraints},
          {"evaluations", o.evaluations},
          {"feasible_evaluations", o.feasible},
          {"failed_evaluations", o.failed},
          {"constraint_handling",
           "the driver minimizes each objective plus penalty_weight * sum max(g, 0)^2; the front "
           "holds the feasible non-dominated designs only"},
          {"reference", o.result.reference},
          {"hypervolume", o.result.hypervolumes},
          {"front_hypervolume", o.front_hypervolume},
          {"knee", o.knee},
          {"front", front},
          {"study_document", study}};
}

namespace {

// Compares one recorded value with its re-evaluation under the report's mode (`tolerance`:
// the design's own, for kTolerance).
void compare_value(ReproduceReport& rep, const std::string& name, double recorded, double got,
                   double tolerance = 0.0) {
  ReproducedValue v{name, recorded, got, 0.0, false};
  if (got == recorded) ++rep.bit_identical;
  if (rep.mode == CompareMode::kBitIdentical) {
    v.ok = got == recorded;
  } else if (rep.mode == CompareMode::kTolerance) {
    v.tolerance = tolerance;
    v.ok = std::abs(got - recorded) <= tolerance;
  } else {
    v.tolerance = rep.rtol * std::abs(recorded) + 1e-12;
    v.ok = std::abs(got - recorded) <= v.tolerance;
  }
  if (!v.ok) ++rep.mismatches;
  rep.values.push_back(v);
}

// Objectives, constraints and metrics of one recorded set against the re-evaluation e.
void compare_set(ReproduceReport& rep, io::JsonReader& r, const json& node, const Study& st,
                 const Evaluation& e, const std::string& prefix, bool named_objectives,
                 const json& tolerance) {
  const auto& ev = st.evaluator;
  // The design's own tolerance of a value (0 when it records none: only bit-identity passes).
  auto tol = [&](const char* kind, const json& key) {
    if (!tolerance.is_object() || !tolerance.contains(kind)) return 0.0;
    const json& t = tolerance.at(kind);
    if (key.is_string() && t.is_object() && t.contains(key.get<std::string>()))
      return t.at(key.get<std::string>()).get<double>();
    if (key.is_number() && t.is_array() && key.get<size_t>() < t.size())
      return t.at(key.get<size_t>()).get<double>();
    return 0.0;
  };
  const json& objectives = node.at("objectives");
  for (size_t j = 0; j < ev.objectives.size(); ++j) {
    const json* v = named_objectives ? (objectives.contains(ev.objectives[j].name)
                                            ? &objectives.at(ev.objectives[j].name)
                                            : nullptr)
                                     : (j < objectives.size() ? &objectives.at(j) : nullptr);
    if (v == nullptr || !v->is_number()) {
      throw io::InputError(r.file(), r.pointer_of("objectives") + "/" +
                                         (named_objectives ? io::pointer_escape(ev.objectives[j].name)
                                                           : std::to_string(j)),
                           "a recorded objective value", v ? io::describe(*v) : "nothing");
    }
    compare_value(rep, prefix + ev.objectives[j].name, v->get<double>(),
                  j < e.objectives.size() ? e.objectives[j] : NAN, tol("objectives", json(j)));
  }
  const json& g = node.at("constraints");
  if (!g.is_array() || g.size() != ev.constraints.size()) {
    throw io::InputError(r.file(), r.pointer_of("constraints"),
                         std::to_string(ev.constraints.size()) + " constraint values",
                         io::describe(g));
  }
  for (size_t c = 0; c < g.size(); ++c)
    compare_value(rep, prefix + "g" + std::to_string(c), g.at(c).get<double>(), e.constraints[c],
                  tol("constraints", json(c)));
  for (auto it = node.at("metrics").begin(); it != node.at("metrics").end(); ++it) {
    const auto found = e.aggregated.find(it.key());
    compare_value(rep, prefix + it.key(), it.value().get<double>(),
                  found != e.aggregated.end() ? found->second : NAN, tol("metrics", json(it.key())));
  }
}

// The per-trial decisions of one recorded set against the re-evaluation e.
void compare_trials(ReproduceReport& rep, const json& recorded, const Evaluation& e,
                    const std::string& set, const json& fragile) {
  const std::vector<TrialDecision> got = trial_decisions(e);
  for (size_t i = 0; i < recorded.size(); ++i) {
    ++rep.trials_compared;
    const json& t = recorded.at(i);
    TrialDecision want{t.value("name", ""), t.value("status", ""), t.value("stabilized", false),
                       t.value("apex_held", false)};
    const TrialDecision have = i < got.size() ? got[i] : TrialDecision{want.name, "none", false, false};
    if (have == want) continue;
    bool is_fragile = false;
    if (fragile.is_array())
      for (const json& f : fragile) is_fragile = is_fragile || (f.is_number() && f.get<size_t>() == i);
    rep.decision_differences.push_back({set, static_cast<long>(i), want, have, is_fragile});
    if (!is_fragile) ++rep.decision_mismatches;
  }
}

}  // namespace

ReproduceReport reproduce_front_design(const json& pareto, const std::string& path, long index,
                                       const ReproduceOptions& opt) {
  opt.validate();
  if (!pareto.is_object() || pareto.value("type", "") != "pronk_pareto") {
    throw io::InputError(path, "/type", "\"pronk_pareto\" (a pareto.json of pronk optimize)",
                         pareto.is_object() && pareto.contains("type")
                             ? io::describe(pareto.at("type"))
                             : "nothing");
  }
  for (const char* key : {"front", "study_document", "commit", "compiler", "build_flags"}) {
    if (!pareto.contains(key))
      throw io::InputError(path, std::string("/") + key, "a recorded value", "nothing");
  }
  const json& front = pareto.at("front");
  if (!front.is_array() || index < 0 || index >= static_cast<long>(front.size())) {
    throw io::InputError(path, "/front",
                         "a front with an index " + std::to_string(index) + " (--front-index)",
                         front.is_array() ? std::to_string(front.size()) + " designs"
                                          : io::describe(front));
  }
  const std::string dir = [&] {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
  }();
  const Study st = parse_study(pareto.at("study_document"), path + "#/study_document", dir);
  if (!st.moo) {
    throw io::InputError(path, "/study_document/optimizer",
                         "a multi-objective study", "a single-objective one");
  }
  const json& d = front.at(static_cast<size_t>(index));
  const std::string at = "/front/" + std::to_string(index);
  io::JsonReader r(d, path, at);
  const Eigen::VectorXd u = r.vector("unit", static_cast<int>(st.evaluator.parameters.size()), 0.0, 1.0);
  const std::vector<double> unit(u.data(), u.data() + u.size());

  ReproduceReport rep;
  const std::string commit = pronk::git_commit(), compiler = compiler_id(),
                    flags = pronk::build_flags();
  const std::string rc = pareto.at("commit").get<std::string>(),
                    rcomp = pareto.at("compiler").get<std::string>(),
                    rflags = pareto.at("build_flags").get<std::string>();
  rep.same_toolchain = rcomp == compiler && rflags == flags;
  rep.same_build = rep.same_toolchain && rc == commit;
  rep.recorded_build = rc + ", " + rcomp + ", " + rflags;
  rep.this_build = commit + ", " + compiler + ", " + flags;
  rep.decisions_recorded = true;
  const json none;
  const json& record = d.contains("reproduction") ? d.at("reproduction") : none;
  const json& val_record =
      record.is_object() && record.contains("validation") ? record.at("validation") : none;
  auto part = [&](const json& j, const char* key) -> const json& {
    return j.is_object() && j.contains(key) ? j.at(key) : none;
  };
  if (opt.rtol) {
    rep.mode = CompareMode::kRelative;
    rep.rtol = *opt.rtol;
  } else if (rep.same_build || (opt.strict && rep.same_toolchain)) {
    rep.mode = CompareMode::kBitIdentical;
  } else if (record.is_object()) {
    rep.mode = CompareMode::kTolerance;
  } else {
    rep.mode = CompareMode::kRelative;
    rep.rtol = kLegacyRtol;
  }
  const DesignEvaluation e = evaluate_design(st, unit, opt.threads, !opt.scenarios_only);
  compare_set(rep, r, d, st, e.scenarios, "", true, part(record, "tolerance"));
  compare_trials(rep, d.at("trials"), e.scenarios, "scenarios", part(record, "fragile_trials"));
  if (st.validation && opt.scenarios_only) {
    rep.validation_skipped = true;
  } else if (st.validation) {
    const json& v = d.at("validation");
    io::JsonReader vr(v, path, at + "/validation");
    compare_set(rep, vr, v, st, *e.validation, "validation ", false, part(val_record, "tolerance"));
    compare_trials(rep, v.at("trials"), *e.validation, "validation",
                   part(val_record, "fragile_trials"));
  }
  return rep;
}

}  // namespace pronk::optimize
