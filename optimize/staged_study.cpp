#include "optimize/staged_study.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/run_output.hpp"
#include "optimize/moo_study.hpp"
#include "optimize/output_lock.hpp"
#include "optimize/progress.hpp"
#include "sim/scene/robot_scaling.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace {

// Keys a stage may set for itself; every other study key is shared by all stages.
const std::vector<std::string>& stage_study_keys() {
  static const std::vector<std::string> keys = {"optimizer",   "scenarios",   "validation",
                                                "stability",   "objective",   "objectives",
                                                "constraints", "fall_penalty"};
  return keys;
}

constexpr const char* kLegStiffness = "/pseudo_rigid/leg_stiffness";

// The study's scene, resolved (every default explicit) with its overrides applied. *given_leg:
// whether the scene (with the overrides) sets the leg stiffness itself.
json resolved_scene(io::JsonReader& r, const json& doc, const std::string& file,
                    const std::string& base_dir, bool* given_leg) {
  std::string scene_file;
  json scene_doc = read_study_scene(r, doc, file, base_dir, &scene_file);
  if (doc.contains("scene_overrides") && doc.at("scene_overrides").is_array()) {
    for (const auto& o : doc.at("scene_overrides"))
      if (o.is_string()) io::apply_override(scene_doc, o.get<std::string>());
  }
  *given_leg = scene_doc.contains(json::json_pointer(kLegStiffness));
  return io::scene_to_json(io::parse_scene(scene_doc, scene_file));
}

// The leg stiffness unless the study fixes it (the scene sets it, or its parameter an
// "initial"): it follows the design's stance time. Records the parameter that tunes it.
void find_following_leg_stiffness(bool given_leg, StagedStudy* st) {
  st->leg_stiffness_follows = !given_leg;
  const json& params = st->document.at("parameters");
  for (size_t i = 0; i < params.size(); ++i) {
    if (params[i].at("pointer") != kLegStiffness) continue;
    st->leg_stiffness_parameter = st->parameters[i].name;
    if (params[i].contains("initial")) st->leg_stiffness_follows = false;
  }
}

// The leg stiffness whose stance half-period is the stance time of `scene` (its pulse duration,
// or the max-force estimate), the rule the full model's expected stance inverts.
double following_leg_stiffness(const json& scene) {
  const scene::Scene s = io::parse_scene(scene, "stage scene");
  return scene::leg_stiffness_for_stance(s, scene::design_stance_time(s));
}

// The study's resolved scene with parameter `values` bound.
json scene_at(const StagedStudy& st, const std::map<std::string, double>& values) {
  json scene = st.scene;
  for (const auto& p : st.parameters) scene[json::json_pointer(p.pointer)] = values.at(p.name);
  return scene;
}

// Name, pointer and starting value of every study parameter (the stages check the rest).
std::vector<Parameter> study_parameters(io::JsonReader& r, const json& doc, const json& scene) {
  if (!doc.contains("parameters") || !doc.at("parameters").is_array() ||
      doc.at("parameters").empty()) {
    throw r.error("parameters", "a non-empty array of parameters",
                  doc.contains("parameters") ? io::describe(doc.at("parameters")) : "nothing");
  }
  std::vector<Parameter> out;
  for (size_t i = 0; i < doc.at("parameters").size(); ++i) {
    const json& p = doc.at("parameters")[i];
    const std::string at = "/parameters/" + std::to_string(i);
    if (!p.is_object() || !p.value("name", json()).is_string() ||
        !p.value("pointer", json()).is_string()) {
      throw io::InputError(r.file(), at, "an object with a \"name\" and a \"pointer\"",
                           io::describe(p));
    }
    Parameter par;
    par.name = p.at("name").get<std::string>();
    par.pointer = p.at("pointer").get<std::string>();
    const json* target = io::find_pointer(scene, par.pointer);
    if (par.pointer.empty() || target == nullptr || !target->is_number()) {
      throw io::InputError(r.file(), at + "/pointer",
                           "a pointer to a number of the scene format (see scene.resolved.json)",
                           "\"" + par.pointer + "\", which names no number of a scene" +
                               io::resolved_pointer_hint(par.pointer));
    }
    const json& init = p.value("initial", json());
    par.initial = init.is_number() ? init.get<double>() : target->get<double>();
    out.push_back(par);
  }
  return out;
}

StageSpec parse_stage(io::JsonReader s, const StagedStudy& st, const json& raw,
                      const std::vector<StageSpec>& earlier) {
  StageSpec stage;
  stage.name = s.string_or("name", "");
  const bool name_ok =
      !stage.name.empty() &&
      stage.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == std::string::npos;
  if (!name_ok) throw s.error("name", "a stage name of [a-z0-9_]", "\"" + stage.name + "\"");
  for (const auto& e : earlier)
    if (e.name == stage.name) throw s.error("name", "a name no earlier stage has", stage.name);
  if (!s.has("model"))
    throw s.error("model", "the stage's model: " + scene::model_names_expected(), "nothing");
  stage.model = s.choice_or("model", "", scene::model_names());
  stage.start = s.string_or("start", "previous");
  bool start_ok = stage.start == "previous" || stage.start == "initial";
  for (const auto& e : earlier) start_ok = start_ok || e.name == stage.start;
  if (!start_ok) {
    throw s.error("start", "\"initial\", \"previous\" or the name of an earlier stage",
                  "\"" + stage.start + "\"");
  }
  if (s.has("parameters")) {
    const json& names = raw.at("parameters");
    s.optional("parameters");
    if (!names.is_array() || names.empty())
      throw s.error("parameters", "a non-empty array of parameter names", io::describe(names));
    for (const auto& n : names) {
      const bool known =
          n.is_string() && std::any_of(st.parameters.begin(), st.parameters.end(),
                                       [&](const Parameter& p) { return p.name == n; });
      if (!known) throw s.error("parameters", "names of the study's parameters", io::describe(n));
      stage.parameters.push_back(n.get<std::string>());
    }
  } else {
    s.optional("parameters");
    for (const auto& p : st.parameters) stage.parameters.push_back(p.name);
  }
  stage.overrides = json::object();
  for (const auto& k : stage_study_keys()) {
    if (raw.contains(k)) stage.overrides[k] = raw.at(k);
    s.optional(k);
  }
  s.string_or("description", "");
  s.finish();
  return stage;
}

}  // namespace

bool is_staged_study(const json& doc) { return doc.is_object() && doc.contains("stages"); }

Study stage_study(const StagedStudy& st, size_t k, const std::map<std::string, double>& values) {
  const StageSpec& stage = st.stages.at(k);
  json d = st.document;
  d["name"] = st.name + "_" + stage.name;
  d["model"] = stage.model;
  for (const auto& [key, v] : stage.overrides.items()) d[key] = v;
  // A stage's own "objectives" (a multi-objective last stage) replaces the shared
  // "objective", and a stage's own "objective" the shared "objectives".
  if (stage.overrides.contains("objectives")) d.erase("objective");
  if (stage.overrides.contains("objective")) d.erase("objectives");
  json scene = scene_at(st, values);
  // A leg stiffness no stage tunes follows the design's stance time in the full model.
  if (stage.model == "pseudo_rigid" && st.leg_stiffness_follows &&
      st.leg_stiffness_parameter.empty()) {
    scene[json::json_pointer(kLegStiffness)] = following_leg_stiffness(scene);
  }
  d["scene"] = scene;
  d.erase("scene_overrides");
  d.erase("output");
  json params = json::array();
  for (const json& p : st.document.at("parameters")) {
    const std::string name = p.at("name").get<std::string>();
    if (std::find(stage.parameters.begin(), stage.parameters.end(), name) == stage.parameters.end())
      continue;
    json q = p;
    q["initial"] = values.at(name);
    params.push_back(q);
  }
  d["parameters"] = params;
  return parse_study(d, st.file + " (stage \"" + stage.name + "\", " + stage.model + " model)",
                     st.base_dir);
}

StagedStudy parse_staged_study(const json& doc, const std::string& file,
                               const std::string& base_dir) {
  StagedStudy st;
  st.file = file;
  st.base_dir = base_dir;
  io::JsonReader r(doc, file, "");
  st.name = r.path_name_or("name", "");  // the default output directory results/<name>
  if (doc.contains("model"))
    throw r.error("model", "a \"model\" in every stage, none at the top",
                  io::describe(doc["model"]));
  st.cross_evaluate = r.boolean_or("cross_evaluate", false);
  bool given_leg = false;
  st.scene = resolved_scene(r, doc, file, base_dir, &given_leg);
  st.parameters = study_parameters(r, doc, st.scene);
  st.original = doc;
  st.document = doc;
  st.document.erase("stages");
  st.document.erase("cross_evaluate");
  find_following_leg_stiffness(given_leg, &st);
  st.output_dir = doc.value("output", "results/" + st.name);
  std::vector<io::JsonReader> stages = r.object_array("stages");
  if (stages.empty()) throw r.error("stages", "at least one stage", "an empty list");
  for (size_t k = 0; k < stages.size(); ++k)
    st.stages.push_back(parse_stage(stages[k], st, doc.at("stages")[k], st.stages));
  std::set<std::string> tuned;
  for (const auto& s : st.stages) tuned.insert(s.parameters.begin(), s.parameters.end());
  for (size_t i = 0; i < st.parameters.size(); ++i) {
    if (!tuned.count(st.parameters[i].name)) {
      throw io::InputError(file, "/parameters/" + std::to_string(i), "a parameter some stage tunes",
                           "\"" + st.parameters[i].name + "\"");
    }
  }
  // Every stage must be a valid study of its own model (from the initial design).
  std::map<std::string, double> initial;
  for (const auto& p : st.parameters) initial[p.name] = p.initial;
  for (size_t k = 0; k < st.stages.size(); ++k) {
    const Study s = stage_study(st, k, initial);
    // The next stage starts from a stage's one design: only the last may be multi-objective.
    if (s.moo && k + 1 < st.stages.size()) {
      throw io::InputError(file, "/stages/" + std::to_string(k) + "/optimizer/algorithm",
                           "a single-objective optimizer (only the last stage may be "
                           "multi-objective: a later stage starts from one design)",
                           "\"" + s.moo->algorithm + "\"");
    }
  }
  return st;
}

namespace {

// The stage a stage starts from (nullptr: the initial design).
const StageOutcome* start_stage(const StagedStudy& st, size_t k,
                                const std::vector<StageOutcome>& done) {
  const std::string& start = st.stages[k].start;
  if (start == "initial" || (start == "previous" && k == 0)) return nullptr;
  if (start == "previous") return &done.back();
  for (const auto& d : done)
    if (d.name == start) return &d;
  return nullptr;  // unreachable: parse_stage checked the name
}

std::map<std::string, double> start_values(const StagedStudy& st, size_t k,
                                           const std::vector<StageOutcome>& done,
                                           const std::map<std::string, double>& initial) {
  const StageOutcome* from = start_stage(st, k, done);
  std::map<std::string, double> values = from ? from->values : initial;
  // From a reduced model into the full model: the tuned leg stiffness starts where the reduced
  // design's stance time puts it (within its bounds), unless the study fixes it.
  if (from && from->model != "pseudo_rigid" && st.stages[k].model == "pseudo_rigid" &&
      st.leg_stiffness_follows && !st.leg_stiffness_parameter.empty()) {
    const std::string& name = st.leg_stiffness_parameter;
    for (const json& p : st.document.at("parameters")) {
      if (p.at("name") != name) continue;
      values[name] = std::clamp(following_leg_stiffness(scene_at(st, values)),
                                p.at("lower").get<double>(), p.at("upper").get<double>());
    }
  }
  return values;
}

json read_design(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return json();
  try {
    return io::read_json_file(path);
  } catch (const io::InputError&) {
    return json();  // torn by a crash: the stage runs again (its journal replays)
  }
}

// The marker a stage writes last, once every one of its files is written: a stage without
// it (killed while writing its results, or stopped) runs again on --resume, its journal
// replaying, and rewrites them all.
constexpr const char* kStageComplete = "/stage_complete.json";

// The finished stage's design.json when DIR holds a stage of `hash` that completed.
json finished_stage(const std::string& dir, const std::string& hash) {
  const json marker = read_design(dir + kStageComplete);
  if (!marker.is_object() || marker.value("study_hash", "") != hash) return json();
  const json done = read_design(dir + "/design.json");
  return done.is_object() && done.value("study_hash", "") == hash ? done : json();
}

StageOutcome run_stage(const StagedStudy& st, size_t k, const std::map<std::string, double>& from,
                       const StudyRunOptions& opt, const std::string& out_dir, bool* stopped) {
  const Study s = stage_study(st, k, from);
  StageOutcome o;
  o.name = st.stages[k].name;
  o.model = st.stages[k].model;
  o.out_dir = out_dir + "/stages/" + std::to_string(k + 1) + "_" + o.name;
  o.values = from;
  // With --verify every stage's journal is checked: finished stages run (replay) again.
  const json done = opt.resume && opt.verify < 0 ? finished_stage(o.out_dir, s.hash) : json();
  if (!done.is_null()) {
    o.design = done;
    o.skipped = true;
  } else {
    std::error_code ec;
    std::filesystem::remove(o.out_dir + kStageComplete, ec);
    StudyRunOptions so = opt;
    so.out_dir = o.out_dir;
    const StudyOutcome r = run_study(s, so);
    const auto status = r.result.status;
    *stopped = status == OptimizerStatus::kStopped || status == OptimizerStatus::kFailed;
    o.design = io::read_json_file(o.out_dir + "/design.json");
    if (!*stopped) {
      const json marker = {
          {"type", "pronk_stage_complete"}, {"stage", o.name}, {"study_hash", s.hash}};
      io::write_file_atomic(o.out_dir + kStageComplete, marker.dump(2) + "\n");
    }
  }
  for (const auto& [name, v] : o.design.at("parameters").items()) o.values[name] = v.get<double>();
  return o;
}

// A design (all parameter values) evaluated by stage k's evaluator (model, scenarios).
Evaluation evaluate_in_stage(const StagedStudy& st, size_t k,
                             const std::map<std::string, double>& values,
                             const StudyRunOptions& opt) {
  EvaluatorConfig cfg = stage_study(st, k, values).evaluator;
  cfg.threads = opt.threads;
  cfg.farm = opt.farm;
  const Evaluator ev(cfg);
  return ev.evaluate_full(ev.initial_point());
}

json evaluation_json(const Evaluation& e) {
  json m = json::object();
  for (const auto& [k, v] : e.aggregated) m[k] = v;
  return {{"cost", e.cost}, {"ok", e.ok}, {"metrics", m}};
}

// A stage's directory as the design and summary record it: relative to the study's own
// output directory, so that a result moved or cloned elsewhere still names its stages.
std::string relative_stage_dir(const std::string& stage_dir, const std::string& out_dir) {
  const std::string prefix = out_dir + "/";
  return stage_dir.rfind(prefix, 0) == 0 ? stage_dir.substr(prefix.size()) : stage_dir;
}

json staged_design(const StagedStudy& st, const StagedOutcome& o, const json& doc) {
  json d = o.stages.back().design;
  json stages = json::array();
  for (const auto& s : o.stages) {
    stages.push_back({{"name", s.name},
                      {"model", s.model},
                      {"directory", relative_stage_dir(s.out_dir, o.out_dir)},
                      {"parameters", s.values},
                      {"cost", s.design.at("cost")},
                      {"initial_cost", s.design.at("initial_cost")},
                      {"metrics", s.design.at("metrics")},
                      {"optimizer", s.design.at("optimizer")},
                      {"stability", s.design.value("stability", json())}});
  }
  d["stages"] = stages;
  d["fidelity_gap"] = {{"model", o.stages.back().model},
                       {"first_stage", o.stages.front().name},
                       {"first_stage_design", evaluation_json(o.gap_first)},
                       {"final_design", evaluation_json(o.final_best)}};
  if (!o.cross.empty()) {
    json rows = json::array();
    for (size_t i = 0; i < o.cross.size(); ++i) {
      json row = json::object();
      for (size_t j = 0; j < o.cross[i].size(); ++j)
        row[o.stages[j].name] = evaluation_json(o.cross[i][j]);
      rows.push_back({{"design", o.stages[i].name}, {"evaluated_by", row}});
    }
    d["cross_evaluation"] = rows;
  }
  d["staged_study"] = st.name;
  d["staged_study_document"] = doc;
  return d;
}

std::string staged_summary(const StagedStudy& st, const StagedOutcome& o) {
  std::ostringstream md;
  md << "# Study `" << st.name << "` (" << o.stages.size() << " stages)\n\n"
     << "| stage | model | evaluations | initial cost | tuned cost | directory |\n"
     << "|---|---|---|---|---|---|\n";
  for (const auto& s : o.stages) {
    md << "| " << s.name << " | " << s.model << " | "
       << s.design.at("optimizer").value("evaluations", 0L) << " | "
       << s.design.value("initial_cost", 0.0) << " | " << s.design.value("cost", 0.0) << " | `"
       << relative_stage_dir(s.out_dir, o.out_dir) << "` |\n";
  }
  md << "\nParameters after each stage:\n\n| parameter |";
  for (const auto& s : o.stages) md << " " << s.name << " |";
  md << "\n|---|";
  for (size_t i = 0; i < o.stages.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& p : st.parameters) {
    md << "| " << p.name << " |";
    for (const auto& s : o.stages) md << " " << s.values.at(p.name) << " |";
    md << "\n";
  }
  md << "\n## Fidelity gap\n\nThe first stage's design (tuned in the " << o.stages.front().model
     << " model) and the final design, both evaluated in the " << o.stages.back().model
     << " model on the last stage's scenarios:\n\n| metric | first stage's design | final design "
        "|\n|---|---|---|\n";
  md << "| cost | " << o.gap_first.cost << " | " << o.final_best.cost << " |\n";
  // Whether the last stage computes the spectral radius, as its study reads it.
  const bool stability =
      stage_study(st, st.stages.size() - 1, o.stages.back().values).evaluator.stability;
  md << metric_rows(o.gap_first.aggregated, o.final_best.aggregated, stability);
  if (!o.cross.empty()) {
    md << "\n## Every design in every model\n\nRows: the stage whose design is evaluated; "
          "columns: the stage (model and scenarios) that evaluates it. Each cell: mean "
          "stabilized fraction / cost.\n\n| design \\ evaluated in |";
    for (const auto& s : o.stages) md << " " << s.name << " (" << s.model << ") |";
    md << "\n|---|";
    for (size_t j = 0; j < o.stages.size(); ++j) md << "---|";
    md << "\n";
    for (size_t i = 0; i < o.cross.size(); ++i) {
      md << "| " << o.stages[i].name << " |";
      for (const Evaluation& e : o.cross[i]) {
        const auto it = e.aggregated.find("stabilized");
        md << " " << (it != e.aggregated.end() ? it->second : 0.0) << " / " << e.cost << " |";
      }
      md << "\n";
    }
  }
  md << "\n`design.json` holds the final design (reproduce with `pronk reproduce " << o.out_dir
     << "/design.json`), every stage's result and this gap.\n";
  return md.str();
}

// What the stages after k still run, for the progress note: each stage's time left is
// estimated once it runs, since models differ in cost by orders of magnitude.
std::string stages_after(const StagedStudy& st, size_t k,
                         const std::map<std::string, double>& initial) {
  std::string out;
  for (size_t j = k + 1; j < st.stages.size(); ++j) {
    const Study s = stage_study(st, j, initial);
    const long budget =
        s.moo ? s.moo->population * (s.moo->generations + 1) : s.optimizer.max_evaluations;
    out += (out.empty() ? "; then " : ", ") + st.stages[j].name + " (" + std::to_string(budget) +
           " evaluations, " + st.stages[j].model + " model)";
  }
  return out;
}

}  // namespace

StagedOutcome run_staged_study(const StagedStudy& st, const StudyRunOptions& opt) {
  const double t0 = monotonic_seconds();
  StagedOutcome o;
  o.out_dir = opt.out_dir.empty() ? st.output_dir : opt.out_dir;
  io::make_directories(o.out_dir + "/stages");
  const OutputLock lock(o.out_dir, "pronk optimize");
  remove_stale_temporaries(o.out_dir, 0);  // each stage cleans its own directory
  std::map<std::string, double> initial;
  for (const auto& p : st.parameters) initial[p.name] = p.initial;
  for (size_t k = 0; k < st.stages.size(); ++k) {
    bool stopped = false;
    progress_note(opt.progress, st.name + ": stage " + std::to_string(k + 1) + "/" +
                                    std::to_string(st.stages.size()) + " " + st.stages[k].name +
                                    " (" + st.stages[k].model + " model), " +
                                    format_duration(monotonic_seconds() - t0) + " elapsed" +
                                    stages_after(st, k, initial));
    const std::map<std::string, double> from = start_values(st, k, o.stages, initial);
    const Study moo = stage_study(st, k, from);
    if (moo.moo) {  // the last stage, multi-objective: its front is the study's result
      StageOutcome so;
      so.name = st.stages[k].name;
      so.model = st.stages[k].model;
      so.out_dir = o.out_dir + "/stages/" + std::to_string(k + 1) + "_" + so.name;
      so.values = from;
      StudyRunOptions mo = opt;
      mo.out_dir = so.out_dir;
      const MooStudyOutcome r = run_moo_study(moo, mo);
      o.stages.push_back(so);
      o.pareto = true;
      o.wall_time = monotonic_seconds() - t0;
      if (r.stopped) {
        o.ok = false;
        return o;
      }
      o.front_size = static_cast<long>(r.front.size());
      o.front_hypervolume = r.front_hypervolume;
      o.knee = r.knee;
      // OUT/pareto.json and pareto.csv: the stage's, reproducible by front index.
      for (const char* f : {"/pareto.json", "/pareto.csv"}) {
        std::ifstream in(so.out_dir + f, std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        if (!in) throw std::runtime_error("cannot read " + so.out_dir + f);
        io::write_file_atomic(o.out_dir + f, text.str());
      }
      return o;
    }
    o.stages.push_back(run_stage(st, k, from, opt, o.out_dir, &stopped));
    if (stopped) {
      o.ok = false;
      o.wall_time = monotonic_seconds() - t0;
      return o;  // the finished stages' results stay on disk; --resume continues
    }
  }
  const size_t last = st.stages.size() - 1;
  if (st.cross_evaluate) {
    o.cross.resize(st.stages.size());
    for (size_t i = 0; i < st.stages.size(); ++i)
      for (size_t j = 0; j < st.stages.size(); ++j)
        o.cross[i].push_back(evaluate_in_stage(st, j, o.stages[i].values, opt));
    // The gap is the table's last column: its first and last rows.
    o.gap_first = o.cross.front()[last];
    o.final_best = o.cross.back()[last];
  } else {
    o.gap_first = evaluate_in_stage(st, last, o.stages.front().values, opt);
    o.final_best = evaluate_in_stage(st, last, o.stages.back().values, opt);
  }
  o.wall_time = monotonic_seconds() - t0;
  io::write_file_atomic(o.out_dir + "/design.json",
                        io::dump_checked(staged_design(st, o, st.original)));
  io::write_file_atomic(o.out_dir + "/summary.md", staged_summary(st, o));
  return o;
}

}  // namespace pronk::optimize
