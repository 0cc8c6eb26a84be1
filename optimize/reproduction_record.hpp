// What a design.json records so that another build can say honestly what it reproduced:
// the per-trial decisions (status, stabilized, apex held) of every scenario and validation
// trial, and a tolerance for every continuous value, measured at recording time by
// re-evaluating the design at points moved by a round-off-sized step (docs/studies.md,
// "Reproducing on another machine").
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/evaluator.hpp"

namespace pronk::optimize {

/// The perturbation run: kPerturbations re-evaluations, each optimizer coordinate moved by
/// ±kPerturbationStep (a signed step per coordinate and perturbation, seeded), so that every
/// parameter moves by about 1e-12 of its range: far above one build's round-off, far below
/// any change a design means. The tolerance of a value is kSafetyFactor times the largest
/// change any of them made to it.
inline constexpr int kPerturbations = 8;
inline constexpr double kPerturbationStep = 1e-12;
inline constexpr double kSafetyFactor = 4.0;

/// One trial's decisions: what `pronk reproduce` on another build must find identical.
struct TrialDecision {
  std::string name;    ///< the scenario's name
  std::string status;  ///< "completed", "fell", "diverged"
  bool stabilized = false;
  bool apex_held = false;
  bool operator==(const TrialDecision&) const = default;
  /// "completed, stabilized, apex held" (or "not stabilized", "apex not held").
  std::string describe() const;
};

/// The decisions of every scenario of an evaluation, in scenario order.
std::vector<TrialDecision> trial_decisions(const Evaluation& e);
nlohmann::json to_json(const std::vector<TrialDecision>& trials);

/// Optimizer coordinates `unit` moved by perturbation k (0 <= k < kPerturbations): every
/// coordinate by exactly kPerturbationStep, the sign drawn from SplitMix64(k), turned
/// inwards at a bound of [0, 1].
std::vector<double> perturbed_unit(const std::vector<double>& unit, int k);

/// {"cost": t, "metrics": {name: t}}: kSafetyFactor times the largest |change| of the cost
/// and of each aggregated metric of `reference` over the `perturbed` evaluations.
nlohmann::json tolerance_json(const Evaluation& reference,
                              const std::vector<Evaluation>& perturbed);

/// Indices of the trials whose decisions some perturbed evaluation changed.
std::vector<long> fragile_trials(const Evaluation& reference,
                                 const std::vector<Evaluation>& perturbed);

/// The design's "reproduction" record: the method and its numbers, the tolerances of the
/// scenario set and (when `validation` is given) of the validation set, and the fragile
/// trials of each. Runs the perturbation run: kPerturbations evaluations of each set.
nlohmann::json record_reproduction(const Evaluator& scenarios, const Evaluation& best,
                                   const Evaluator* validation, const Evaluation* validation_best);

}  // namespace pronk::optimize
