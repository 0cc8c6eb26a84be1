// Multi-fidelity studies: a study with "stages", each its own model, optimizer,
// budget and scenarios, run one after the other. Each stage is an ordinary
// single-model study (study.hpp) whose scene carries the design the stage starts
// from, run by run_study into OUT/stages/<k>_<name>/ with its own journal, so
// --resume replays every stage byte for byte. OUT/design.json is the last stage's
// design (`pronk reproduce` checks it) plus every stage's result and the fidelity
// gap: the first stage's design re-evaluated in the last stage's model. With
// "cross_evaluate": true every stage's design is also evaluated by every stage's
// evaluator (its model and scenarios): how far a design tuned in a cheap model
// can be trusted in a detailed one.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"

namespace pronk::optimize {

struct StageSpec {
  std::string name;
  std::string model;                    ///< impulse, pulse or pseudo_rigid
  std::string start;                    ///< "initial", "previous" or an earlier stage's name
  std::vector<std::string> parameters;  ///< the study's parameters this stage tunes
  nlohmann::json overrides;             ///< study keys the stage replaces (optimizer, ...)
};

struct StagedStudy {
  std::string name;
  std::string file;
  std::string base_dir;               ///< resolves the scene path
  nlohmann::json original;            ///< the study as read
  nlohmann::json document;            ///< the study without "stages"
  nlohmann::json scene;               ///< resolved scene, overrides applied
  std::vector<Parameter> parameters;  ///< of the whole study (initial values from it)
  std::vector<StageSpec> stages;
  std::string output_dir;
  bool cross_evaluate = false;  ///< evaluate every stage's design in every stage
  /// The full model's leg stiffness follows the design's stance time (the scene does not set
  /// it, nor its parameter an "initial"): k = m (pi / Ts)^2 / n, Ts the pulse duration (or
  /// the max-force estimate). Tuned (leg_stiffness_parameter), it starts there when a stage
  /// goes from a reduced model to the full model; untuned, every full-model stage uses it.
  bool leg_stiffness_follows = false;
  std::string leg_stiffness_parameter;  ///< the parameter that tunes it, if any
};

/// True when the study document has "stages".
bool is_staged_study(const nlohmann::json& doc);

/// Reads a staged study and checks every stage as a study of its own (its model
/// uses every parameter it tunes, its keys are known, its start exists).
/// Throws io::InputError naming the file, pointer, expected and found.
StagedStudy parse_staged_study(const nlohmann::json& doc, const std::string& file,
                               const std::string& base_dir);

/// The single-model study of stage k, starting from `values` (parameter name -> value).
Study stage_study(const StagedStudy& st, size_t k, const std::map<std::string, double>& values);

struct StageOutcome {
  std::string name, model, out_dir;
  std::map<std::string, double> values;  ///< every parameter after the stage
  nlohmann::json design;                 ///< the stage's design.json
  bool skipped = false;                  ///< taken from a finished stage on --resume
};

struct StagedOutcome {
  std::vector<StageOutcome> stages;
  Evaluation gap_first;   ///< the first stage's design in the last stage's model
  Evaluation final_best;  ///< the last stage's design, same evaluator
  /// With cross_evaluate: cross[i][j] = stage i's design evaluated by stage j.
  std::vector<std::vector<Evaluation>> cross;
  std::string out_dir;
  double wall_time = 0.0;  ///< [s]
  bool ok = true;          ///< every stage's optimizer finished (not stopped or failed)
  /// The last stage is multi-objective: OUT/pareto.json and pareto.csv are the result (its
  /// stage's), no design.json, no fidelity gap (gap_first, final_best, cross stay empty).
  bool pareto = false;
  long front_size = 0;
  double front_hypervolume = 0.0;
  long knee = -1;
};

/// Runs every stage (resuming finished ones with options.resume), then writes
/// OUT/design.json and OUT/summary.md.
StagedOutcome run_staged_study(const StagedStudy& st, const StudyRunOptions& options);

}  // namespace pronk::optimize
