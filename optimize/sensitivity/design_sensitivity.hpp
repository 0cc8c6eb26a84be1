// The sensitivity of a tuned design (design.json of `pronk optimize`) to its numbers: the
// study's tuned parameters at the design's values, and physical numbers of the scene named by
// JSON Pointer (by default the body's mass and principal moments of inertia, and in the full
// model the leg stiffness and the friction), each with a relative range.
//
// Every evaluation runs the design's study (its scenarios, or its validation set) with the
// numbers bound into the resolved scene, robot and controller alike: the design as it would be
// with that number changed. All evaluations share the scenarios (common random numbers), so
// differences are the numbers' effects, not the disturbances'. Deterministic: the same
// numbers whatever the thread count (the evaluator's own guarantee, points by index).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/job_farm.hpp"
#include "optimize/progress.hpp"
#include "optimize/sensitivity/local.hpp"
#include "optimize/sensitivity/sobol.hpp"

namespace pronk::optimize::sensitivity {

/// One number the outputs are differentiated by.
struct SensitivityInput {
  std::string name;     ///< the study's parameter name, or a name for a physical number
  std::string pointer;  ///< into the resolved scene
  bool tuned = false;   ///< a parameter of the study (false: a physical number)
  double value = 0.0;   ///< at the design
  double range = 0.1;   ///< relative half-width of the global range (absolute when value is 0)
  double lower = 0.0, upper = 0.0;  ///< the global range
};

struct DesignSensitivityOptions {
  std::optional<std::string> model;  ///< evaluate in this model instead of the study's
  bool validation = false;           ///< on the study's validation set
  /// true: a physical number changes the robot only, the controller keeps the design's
  /// numbers (a plant draw, as robust-design perturbations; the stability analysis sees the
  /// design's robot); false: the design with that number, robot and controller alike.
  bool plant = true;
  LocalOptions local;
  SobolOptions sobol;  ///< sobol.samples == 0: no global analysis
  double default_range = 0.1;
  /// --range POINTER=REL: the range of an input, or a physical number added as an input.
  std::vector<std::pair<std::string, double>> ranges;
  /// --inputs: only these inputs (pointers: a tuned parameter's, or a physical number of the
  /// resolved scene, added with the default range); empty: every default input.
  std::vector<std::string> only;
  int threads = 1;
  /// Where the evaluations' scenario runs go instead of the threads (MPI ranks); the numbers
  /// are the same either way.
  JobFarm* farm = nullptr;
  ProgressStyle progress = ProgressStyle::kOff;
  /// Throws io::InputError naming the option.
  void validate() const;
};

struct DesignSensitivity {
  std::string design_path, study, model, set;  ///< set: "scenarios" or "validation"
  long scenarios = 0;
  std::vector<SensitivityInput> inputs;
  std::vector<std::string> outputs;  ///< "cost", then every aggregated metric (sorted)
  LocalResult local;
  double local_step = 0.0;  ///< the relative step h (the differences use h and h/2)
  /// One at a time: the outputs with input j at its range's lower and upper end ([out][in]).
  std::vector<std::vector<double>> low, high;
  std::optional<SobolResult> sobol;
  bool plant = true;  ///< how the physical numbers were changed (options.plant)
  SobolOptions sobol_options;
  long evaluations = 0;
  long failed = 0;                    ///< evaluations that made no valid scene (their outputs NaN)
  std::vector<std::string> failures;  ///< the first few reasons
  double local_seconds = 0.0, sobol_seconds = 0.0;
};

/// Reads `design` (from `path`, named in errors) and computes its sensitivities. Throws
/// io::InputError for a bad design or bad options (naming the option or the JSON Pointer).
DesignSensitivity design_sensitivity(const nlohmann::json& design, const std::string& path,
                                     const DesignSensitivityOptions& options);

/// Parses "POINTER=REL" (--range). Throws io::InputError.
std::pair<std::string, double> parse_range_option(const std::string& text);

}  // namespace pronk::optimize::sensitivity
