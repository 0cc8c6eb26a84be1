#include "optimize/compare.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace {

// The study keys that judge a design: every design runs the reference study's.
const std::vector<std::string>& judging_keys() {
  static const std::vector<std::string> keys = {"scenarios",   "validation", "objective",
                                                "constraints", "stability",  "fall_penalty"};
  return keys;
}

constexpr long kMaxSeed = 9007199254740991L;  // what a study's "seed" accepts (2^53 - 1)

// "scenarios:I" or "validation:I" as {set, I}; nothing for any other text.
std::optional<std::pair<std::string, long>> parse_play(const std::string& play) {
  const size_t colon = play.find(':');
  if (colon == std::string::npos) return std::nullopt;
  const std::string set = play.substr(0, colon), index = play.substr(colon + 1);
  if (set != "scenarios" && set != "validation") return std::nullopt;
  if (index.empty() || index.size() > 9 ||
      index.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::make_pair(set, std::strtol(index.c_str(), nullptr, 10));
}

std::string model_of(const Study& s) { return s.evaluator.scene_doc.value("model", std::string()); }

// The reference study's judging keys, with --trials and --seed applied to its validation set.
json reference_judging(const json& ref_doc, const CompareOptions& opt, const std::string& ref) {
  json out = json::object();
  for (const std::string& k : judging_keys()) {
    if (ref_doc.contains(k)) out[k] = ref_doc.at(k);
  }
  if (opt.trials == 0 && !opt.seed) return out;
  const bool has_set = out.contains("validation") && out["validation"].is_object();
  if (!has_set || !out["validation"].contains("random")) {
    throw io::InputError(
        opt.trials > 0 ? "--trials" : "--seed", "",
        "a reference design whose study has a validation set of random trials",
        ref + ", whose study has " +
            (has_set ? "a validation set without random trials" : "no validation set"));
  }
  if (opt.trials > 0) out["validation"]["random"]["count"] = opt.trials;
  if (opt.seed) out["validation"]["random"]["seed"] = *opt.seed;
  return out;
}

// The study design `d` runs: its own study with the judging keys replaced and, with a model
// given, that model set as a stage sets it. parse_study checks everything against the model.
Study judged_study(const ComparedDesign& d, const json& judging, const CompareOptions& opt,
                   const std::string& ref_file, bool* own) {
  const json& own_doc = d.recorded.study.document;
  json doc = own_doc;
  for (const std::string& k : judging_keys()) {
    if (judging.contains(k)) {
      doc[k] = judging.at(k);
    } else {
      doc.erase(k);
    }
  }
  if (!opt.model.empty()) doc["model"] = opt.model;
  for (const std::string& o : opt.scene_overrides) doc["scene_overrides"].push_back(o);
  std::string name = d.file + "#/study_document";
  if (doc != own_doc) {
    name += " (run on the trials of " + ref_file;
    if (!opt.model.empty()) name += ", in the " + opt.model + " model";
    for (const std::string& o : opt.scene_overrides) name += ", --set " + o;
    name += ")";
  }
  const std::string dir = std::filesystem::path(d.file).parent_path().string();
  Study s = parse_study(doc, name, dir.empty() ? "." : dir);
  json a = doc, b = own_doc;
  a.erase("model");
  b.erase("model");
  *own = a == b && model_of(s) == model_of(d.recorded.study);
  return s;
}

// Column names: each design's label, a repeated one numbered (_2, _3, ...).
void assign_labels(std::vector<ComparedDesign>& designs) {
  std::set<std::string> used;
  for (ComparedDesign& d : designs) {
    const std::string base = design_label(d.file);
    std::string label = base;
    for (int n = 2; used.count(label); ++n) label = base + "_" + std::to_string(n);
    used.insert(label);
    d.label = label;
  }
}

// The trial played back, checked against the sets every design runs.
PlaybackTrial playback_trial(const CompareOptions& opt, const Study& judged) {
  PlaybackTrial p;
  const auto play = parse_play(opt.play);
  if (!play) return p;  // "nominal" (validate() refused anything else)
  const ScenarioSet* set = play->first == "scenarios" ? &judged.evaluator.scenarios
                           : judged.validation        ? &*judged.validation
                                                      : nullptr;
  const long n = set ? static_cast<long>(set->scenarios.size()) : 0;
  if (play->second >= n) {
    throw io::InputError(
        "--play", "",
        set ? "a trial of the " +
                  std::string(play->first == "scenarios" ? "scenarios" : "validation set") +
                  " (0 to " + std::to_string(n - 1) + ")"
            : "\"nominal\" or scenarios:I (the reference study has no "
              "validation set)",
        "\"" + opt.play + "\"");
  }
  p.set = play->first;
  p.index = play->second;
  p.name = set->scenarios[static_cast<size_t>(p.index)].name;
  return p;
}

// What a reader of the comparison must know.
std::vector<std::string> comparison_notes(const Comparison& c, const CompareOptions& opt) {
  std::vector<std::string> notes;
  std::set<std::string> models;
  std::string list;
  for (const ComparedDesign& d : c.designs) {
    models.insert(model_of(d.judged));
    list += (list.empty() ? "" : ", ") + d.label + " " + model_of(d.judged);
  }
  if (models.size() > 1) {
    notes.push_back("The designs ran in different models (" + list +
                    "): their numbers differ by model as well as by design; --model runs them "
                    "all in one.");
  }
  for (const ComparedDesign& d : c.designs) {
    if (d.own_study) continue;
    notes.push_back(d.label + " ran on other trials, objective or model than its own study's (`" +
                    d.recorded.study.name +
                    "`): its numbers here are not the ones its design.json records.");
  }
  if (!c.designs.front().judged.validation) {  // every design runs the same sets
    notes.push_back("The reference study has no validation set: only its scenarios ran.");
  }
  if (opt.trials > 0 || opt.seed) {
    notes.push_back("The reference study's validation set was redrawn (--trials, --seed).");
  }
  return notes;
}

}  // namespace

std::string design_label(const std::string& file) {
  const std::filesystem::path p = std::filesystem::path(file).lexically_normal();
  std::string name = p.parent_path().filename().string();
  if (name.empty() || name == "." || name == "..") {
    name = std::filesystem::absolute(p).parent_path().filename().string();
  }
  if (name.empty() || name == "." || name == "..") name = p.stem().string();
  for (char& ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                    (ch >= '0' && ch <= '9') || ch == '_' || ch == '.' || ch == '-';
    if (!ok) ch = '_';
  }
  return name.empty() ? "design" : name;
}

void CompareOptions::validate(size_t designs) const {
  if (designs < 2) {
    throw io::InputError("command line", "", "at least two design.json files to compare",
                         std::to_string(designs));
  }
  if (!model.empty() && model != "impulse" && model != "pulse" && model != "pseudo_rigid" &&
      model != "mujoco") {
    throw io::InputError("--model", "", "impulse, pulse, pseudo_rigid or mujoco",
                         "\"" + model + "\"");
  }
  if (reference < 1 || static_cast<size_t>(reference) > designs) {
    throw io::InputError("--reference", "",
                         "a design's position on the command line, 1 to " + std::to_string(designs),
                         std::to_string(reference));
  }
  if (trials < 0 || trials > 1000000) {
    throw io::InputError("--trials", "", "a number of trials, 1 to 1000000",
                         std::to_string(trials));
  }
  if (seed && *seed > static_cast<std::uint64_t>(kMaxSeed)) {
    throw io::InputError("--seed", "", "a seed from 0 to 9007199254740991", std::to_string(*seed));
  }
  if (play != "nominal" && !parse_play(play)) {
    throw io::InputError("--play", "", "nominal, scenarios:I or validation:I", "\"" + play + "\"");
  }
  if (threads < 1) {
    throw io::InputError("--threads", "", "a thread count >= 1", std::to_string(threads));
  }
}

Comparison compare_designs(const std::vector<std::string>& files, const CompareOptions& opt) {
  opt.validate(files.size());
  Comparison c;
  c.model = opt.model;
  // Every design read and checked before anything runs: a bad one is the first error.
  for (const std::string& f : files) {
    ComparedDesign d;
    d.file = f;
    d.recorded = read_design(io::read_json_file(f), f);
    c.designs.push_back(std::move(d));
  }
  assign_labels(c.designs);
  // The reference study's (redrawn) trials, objective and constraints judge every design.
  const size_t ref = static_cast<size_t>(opt.reference - 1);
  c.reference_file = c.designs[ref].file;
  c.reference_study = c.designs[ref].recorded.study.name;
  const json judging =
      reference_judging(c.designs[ref].recorded.study.document, opt, c.reference_file);
  for (ComparedDesign& d : c.designs) {
    d.judged = judged_study(d, judging, opt, c.reference_file, &d.own_study);
  }
  c.playback = playback_trial(opt, c.designs[ref].judged);
  const Study& judge = c.designs[ref].judged;
  progress_note(
      opt.progress,
      "compare: " + std::to_string(c.designs.size()) + " designs on the trials of " +
          c.reference_file + ": " + std::to_string(judge.evaluator.scenarios.scenarios.size()) +
          " scenarios" +
          (judge.validation
               ? " and " + std::to_string(judge.validation->scenarios.size()) + " validation trials"
               : std::string()) +
          " each");
  const long sets = judge.validation ? 2 : 1;
  const long total = sets * static_cast<long>(c.designs.size());
  Progress progress(opt.progress, "compare: evaluation", total);
  long done = 0;
  for (ComparedDesign& d : c.designs) {
    d.evaluation = evaluate_design(d.judged, d.recorded.unit, opt.threads);
    done += sets;
    progress.update(done, d.label + " in the " + model_of(d.judged) + " model");
  }
  progress.finish();
  c.notes = comparison_notes(c, opt);
  return c;
}

scene::Scene playback_scene(const Comparison& c, size_t k) {
  const ComparedDesign& d = c.designs.at(k);
  EvaluatorConfig cfg = d.judged.evaluator;
  cfg.threads = 1;
  const Evaluator ev(cfg);
  const bool validation = c.playback.set != "scenarios" && d.judged.validation;
  const ScenarioSet& set = validation ? *d.judged.validation : cfg.scenarios;
  Scenario nominal;
  nominal.name = "nominal";
  const Scenario& trial =
      c.playback.index < 0 ? nominal : set.scenarios.at(static_cast<size_t>(c.playback.index));
  return apply_scenario(ev.scene_at(d.recorded.unit), trial, set);
}

}  // namespace pronk::optimize
