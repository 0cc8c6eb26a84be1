// Reproducing a tuned design (design.json of `pronk optimize`): the design is read and checked
// (optimize/design_reader.hpp), re-evaluated on its study's scenarios and validation set, and
// compared in two parts: every per-trial decision (status, stabilized, apex held), which must
// be identical unless the design's own perturbation run changed it too (a fragile trial:
// reported, not required), and every recorded cost and metric, which must be
//   - bit-identical on the recording build (same commit, compiler and flags);
//   - within the tolerance the design records for it (its perturbation run) on another build;
//   - within a plain relative tolerance when one is given (--rtol), or for a design recorded
//     before pronk recorded tolerances (1e-6; its decisions cannot be compared).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/reproduction_record.hpp"
#include "optimize/study.hpp"

namespace pronk::optimize {

struct ReproduceOptions {
  int threads = 1;
  /// Given: every value compared at this relative tolerance instead of the design's own.
  std::optional<double> rtol;
  /// Bit-identity also on a later commit when the compiler and flags are the recording
  /// build's: then only a change of the code can move a number (what CI checks).
  bool strict = false;
  /// Re-evaluate the study's scenarios only, not its validation set.
  bool scenarios_only = false;
  /// Throws io::InputError (naming "--rtol") unless rtol, when given, is finite and > 0.
  void validate() const;
};

/// The relative tolerance of designs recorded before pronk recorded their own tolerances.
inline constexpr double kLegacyRtol = 1e-6;

enum class CompareMode {
  kBitIdentical,  ///< the recording build (or --strict on its toolchain)
  kTolerance,     ///< another build: the design's recorded tolerances
  kRelative,      ///< --rtol, or a design without recorded tolerances
};

struct ReproducedValue {
  std::string name;  ///< "cost", a metric, or "validation <metric>"
  double recorded = 0.0;
  double reproduced = 0.0;  ///< NaN when the re-evaluation no longer reports the metric
  double tolerance = 0.0;   ///< the largest |difference| accepted (0 when bit-identical)
  bool ok = false;
};

/// A trial whose decisions differ from the recorded ones.
struct DecisionDifference {
  std::string set;  ///< "scenarios" or "validation"
  long index = 0;
  TrialDecision recorded, reproduced;  ///< reproduced.status "none": no such trial ran
  bool fragile = false;  ///< its decisions changed in the recording's perturbation run too
};

struct ReproduceReport {
  CompareMode mode = CompareMode::kBitIdentical;
  bool same_build = false;      ///< commit, compiler and flags of the recording build
  bool same_toolchain = false;  ///< compiler and flags of the recording build
  std::string recorded_build;   ///< "commit, compiler, flags" of the design
  std::string this_build;
  double rtol = 0.0;  ///< in kRelative mode
  std::vector<ReproducedValue> values;
  long mismatches = 0;     ///< values not within their tolerance
  long bit_identical = 0;  ///< values equal to the last bit
  bool decisions_recorded = false;
  long trials_compared = 0;
  std::vector<DecisionDifference> decision_differences;  ///< fragile ones included
  long decision_mismatches = 0;     ///< differences in trials that are not fragile
  bool validation_skipped = false;  ///< --scenarios-only on a design with validation
  bool reproduced() const { return mismatches == 0 && decision_mismatches == 0; }
};

/// A design's optimizer coordinates evaluated on a study's scenarios and (when the study has
/// one and `validation`) its validation set: what `reproduce` compares with the recorded
/// values and `compare` tabulates. Deterministic whatever `threads`.
struct DesignEvaluation {
  Evaluation scenarios;
  std::optional<Evaluation> validation;
};
DesignEvaluation evaluate_design(const Study& study, const std::vector<double>& unit, int threads,
                                 bool validation = true);

/// Re-evaluates `design` (read from `path`, named in errors; a relative scene path of its
/// study resolves against the path's directory). Throws io::InputError when it is not a
/// consistent design.json, or for invalid options.
ReproduceReport reproduce_design(const nlohmann::json& design, const std::string& path,
                                 const ReproduceOptions& options);

}  // namespace pronk::optimize
