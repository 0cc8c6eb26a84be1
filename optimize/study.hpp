// Study files (docs/studies.md): the scene, parameters, scenarios, objective,
// constraints, optimizer and output directory of one optimization, loaded
// with the error discipline of docs/reliability.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/evaluator.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/pareto/moo_options.hpp"
#include "io/load/json_reader.hpp"

namespace pronk::optimize {

struct Study {
  std::string name;
  std::string file;           ///< where it was read from
  nlohmann::json document;    ///< the study as read (after --set overrides)
  std::string hash;           ///< FNV-1a 64 of the canonical study + scene documents (hex)
  EvaluatorConfig evaluator;  ///< scene document, parameters, scenarios, objective, constraints
  OptimizerOptions optimizer;
  /// A multi-objective study (pagmo "nsga2", "moead" or "nspso" over evaluator.objectives,
  /// docs/pareto.md): the driver's options. optimizer holds its library, algorithm, seed
  /// and penalty_weight. Absent for single-objective studies.
  std::optional<pareto::MooOptions> moo;
  /// Held-out scenarios the initial and the tuned design are checked on after
  /// the optimization (not seen by the optimizer).
  std::optional<ScenarioSet> validation;
  std::string output_dir;  ///< default results/<name>
};

/// Reads a study file; `overrides` are "--set /ptr=value" applied to the study
/// document (e.g. /optimizer/max_evaluations=50). Scene paths are relative to
/// the study file. Throws io::InputError on bad input.
Study load_study(const std::string& path, const std::vector<std::string>& overrides = {});

/// Parses a study document (already read); `base_dir` resolves a relative scene path.
Study parse_study(const nlohmann::json& doc, const std::string& file, const std::string& base_dir);

/// The scene document of study `doc` (read by `r`): a file path relative to base_dir, or
/// an inline object; *scene_file names it in error messages. Throws io::InputError.
nlohmann::json read_study_scene(io::JsonReader& r, const nlohmann::json& doc,
                                const std::string& file, const std::string& base_dir,
                                std::string* scene_file);

/// Applies the study's optional "scene_overrides" (an array of "/ptr=value" strings, read by
/// `r`) to *scene_doc. Throws io::InputError.
void apply_study_scene_overrides(io::JsonReader& r, const nlohmann::json& doc,
                                 const std::string& file, nlohmann::json* scene_doc);

/// 64-bit FNV-1a of a string, as 16 hex digits.
std::string fnv1a_hex(const std::string& text);

}  // namespace pronk::optimize
