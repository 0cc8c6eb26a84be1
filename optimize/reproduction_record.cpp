#include "optimize/reproduction_record.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "optimize/scenario.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace {

// A per-trial 0/1 metric as a decision (absent: false, as a failed evaluation reports none).
bool flag(const MetricMap& m, const char* name) {
  const auto it = m.find(name);
  return it != m.end() && it->second != 0.0;
}

}  // namespace

std::string TrialDecision::describe() const {
  return status + (stabilized ? ", stabilized" : ", not stabilized") +
         (apex_held ? ", apex held" : ", apex not held");
}

std::vector<TrialDecision> trial_decisions(const Evaluation& e) {
  std::vector<TrialDecision> out;
  out.reserve(e.scenarios.size());
  for (const ScenarioOutcome& s : e.scenarios) {
    out.push_back({s.name, s.status, flag(s.metrics, "stabilized"), flag(s.metrics, "apex_held")});
  }
  return out;
}

json to_json(const std::vector<TrialDecision>& trials) {
  json out = json::array();
  for (const TrialDecision& t : trials) {
    out.push_back({{"name", t.name},
                   {"status", t.status},
                   {"stabilized", t.stabilized},
                   {"apex_held", t.apex_held}});
  }
  return out;
}

std::vector<double> perturbed_unit(const std::vector<double>& unit, int k) {
  SplitMix64 rng(mix_seed(0x7265'7072'6f64ULL, static_cast<std::uint64_t>(k)));
  std::vector<double> out = unit;
  for (double& x : out) {
    double step = (rng.next() & 1U) ? kPerturbationStep : -kPerturbationStep;
    if (x + step > 1.0 || x + step < 0.0) step = -step;  // stay inside the bounds
    x += step;
  }
  return out;
}

json tolerance_json(const Evaluation& reference, const std::vector<Evaluation>& perturbed) {
  double cost = 0.0;
  std::map<std::string, double> spread;
  for (const auto& [name, v] : reference.aggregated) spread[name] = 0.0;
  for (const Evaluation& e : perturbed) {
    cost = std::max(cost, std::abs(e.cost - reference.cost));
    for (auto& [name, s] : spread) {
      const auto it = e.aggregated.find(name);
      if (it != e.aggregated.end())
        s = std::max(s, std::abs(it->second - reference.aggregated.at(name)));
    }
  }
  json metrics = json::object();
  for (const auto& [name, s] : spread) metrics[name] = kSafetyFactor * s;
  return {{"cost", kSafetyFactor * cost}, {"metrics", metrics}};
}

std::vector<long> fragile_trials(const Evaluation& reference,
                                 const std::vector<Evaluation>& perturbed) {
  const std::vector<TrialDecision> ref = trial_decisions(reference);
  std::vector<long> out;
  for (size_t i = 0; i < ref.size(); ++i) {
    const bool flips = std::any_of(perturbed.begin(), perturbed.end(), [&](const Evaluation& e) {
      return i >= e.scenarios.size() || trial_decisions(e)[i] != ref[i];
    });
    if (flips) out.push_back(static_cast<long>(i));
  }
  return out;
}

json record_reproduction(const Evaluator& scenarios, const Evaluation& best,
                         const Evaluator* validation, const Evaluation* validation_best) {
  std::vector<std::vector<double>> units;
  for (int k = 0; k < kPerturbations; ++k) units.push_back(perturbed_unit(best.unit, k));
  const std::vector<Evaluation> moved = scenarios.evaluate_full_batch(units);
  json record = {{"method", "perturbation"},
                 {"perturbations", kPerturbations},
                 {"step", kPerturbationStep},
                 {"safety_factor", kSafetyFactor},
                 {"tolerance", tolerance_json(best, moved)},
                 {"fragile_trials", fragile_trials(best, moved)},
                 {"validation", nullptr}};
  if (validation != nullptr && validation_best != nullptr) {
    const std::vector<Evaluation> moved_val = validation->evaluate_full_batch(units);
    record["validation"] = {{"tolerance", tolerance_json(*validation_best, moved_val)},
                            {"fragile_trials", fragile_trials(*validation_best, moved_val)}};
  }
  return record;
}

}  // namespace pronk::optimize
