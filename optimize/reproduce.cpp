#include "optimize/reproduce.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "optimize/design_reader.hpp"
#include "optimize/study_runner.hpp"

namespace pronk::optimize {

namespace {

std::string build_text(const std::string& commit, const std::string& compiler,
                       const std::string& flags) {
  return commit + ", " + compiler + ", " + (flags.empty() ? "flags not recorded" : flags);
}

// Compares one recorded set (cost and metrics) with its re-evaluation `e`.
void compare_values(ReproduceReport& rep, const RecordedSet& set, const Evaluation& e,
                    const std::string& prefix) {
  auto compare = [&](const std::string& name, double recorded, double got, double tolerance) {
    const double diff = std::abs(got - recorded);
    ReproducedValue v{prefix + name, recorded, got, 0.0, false};
    if (got == recorded) ++rep.bit_identical;
    switch (rep.mode) {
      case CompareMode::kBitIdentical:
        v.ok = got == recorded;
        break;
      case CompareMode::kTolerance:
        v.tolerance = tolerance;
        v.ok = diff <= tolerance;
        break;
      case CompareMode::kRelative:
        v.tolerance = rep.rtol * std::abs(recorded) + 1e-12;
        v.ok = diff <= v.tolerance;
        break;
    }
    if (!v.ok) ++rep.mismatches;
    rep.values.push_back(v);
  };
  compare("cost", set.cost, e.cost, set.cost_tolerance.value_or(0.0));
  for (const auto& [k, recorded] : set.metrics) {
    const auto it = e.aggregated.find(k);
    const auto tol = set.tolerances.find(k);
    compare(k, recorded, it != e.aggregated.end() ? it->second : NAN,
            tol != set.tolerances.end() ? tol->second : 0.0);
  }
}

// Compares one set's recorded per-trial decisions with its re-evaluation `e`.
void compare_decisions(ReproduceReport& rep, const RecordedSet& set, const Evaluation& e,
                       const std::string& set_name) {
  if (!set.trials) return;
  const std::vector<TrialDecision> got = trial_decisions(e);
  for (size_t i = 0; i < set.trials->size(); ++i) {
    ++rep.trials_compared;
    const TrialDecision& recorded = (*set.trials)[i];
    const TrialDecision reproduced =
        i < got.size() ? got[i] : TrialDecision{recorded.name, "none", false, false};
    if (reproduced == recorded) continue;
    const bool fragile = std::find(set.fragile.begin(), set.fragile.end(), static_cast<long>(i)) !=
                         set.fragile.end();
    rep.decision_differences.push_back(
        {set_name, static_cast<long>(i), recorded, reproduced, fragile});
    if (!fragile) ++rep.decision_mismatches;
  }
}

// How the values are compared: bit for bit on the recording build, else the design's
// tolerances, else a plain relative tolerance.
void choose_mode(ReproduceReport& rep, const RecordedDesign& d, const ReproduceOptions& opt) {
  const std::string commit = pronk::git_commit(), compiler = compiler_id(),
                    flags = pronk::build_flags();
  rep.same_toolchain = d.compiler == compiler && d.build_flags == flags;
  rep.same_build = rep.same_toolchain && d.commit == commit;
  rep.recorded_build = build_text(d.commit, d.compiler, d.build_flags);
  rep.this_build = build_text(commit, compiler, flags);
  rep.decisions_recorded = d.has_reproduction_record();
  if (opt.rtol) {
    rep.mode = CompareMode::kRelative;
    rep.rtol = *opt.rtol;
  } else if (rep.same_build || (opt.strict && rep.same_toolchain)) {
    rep.mode = CompareMode::kBitIdentical;
  } else if (d.has_reproduction_record()) {
    rep.mode = CompareMode::kTolerance;
  } else {
    rep.mode = CompareMode::kRelative;
    rep.rtol = kLegacyRtol;
  }
}

}  // namespace

void ReproduceOptions::validate() const {
  if (rtol && !(std::isfinite(*rtol) && *rtol > 0.0)) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%g", *rtol);
    throw io::InputError("--rtol", "", "a finite relative tolerance > 0", buf);
  }
}

DesignEvaluation evaluate_design(const Study& study, const std::vector<double>& unit, int threads,
                                 bool validation) {
  EvaluatorConfig cfg = study.evaluator;
  cfg.threads = threads;
  DesignEvaluation out;
  out.scenarios = Evaluator(cfg).evaluate_full(unit);
  if (validation && study.validation) {
    out.validation = validation_evaluator(study, threads).evaluate_full(unit);
  }
  return out;
}

ReproduceReport reproduce_design(const nlohmann::json& design, const std::string& path,
                                 const ReproduceOptions& opt) {
  opt.validate();
  const RecordedDesign d = read_design(design, path);
  ReproduceReport rep;
  choose_mode(rep, d, opt);
  const DesignEvaluation e = evaluate_design(d.study, d.unit, opt.threads, !opt.scenarios_only);
  compare_values(rep, d.scenarios, e.scenarios, "");
  compare_decisions(rep, d.scenarios, e.scenarios, "scenarios");
  if (d.validation && opt.scenarios_only) {
    rep.validation_skipped = true;
  } else if (d.validation) {
    compare_values(rep, *d.validation, *e.validation, "validation ");
    compare_decisions(rep, *d.validation, *e.validation, "validation");
  }
  return rep;
}

}  // namespace pronk::optimize
