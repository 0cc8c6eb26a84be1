// A study's validation: the starting and the tuned design on the held-out trials, with its
// progress on stderr (trial runs done of all, time elapsed and left).
#pragma once

#include <optional>

#include "optimize/evaluator.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"

namespace pronk::optimize {

/// Evaluates o.initial and o.best (and, with "compare_nominal" on a set that perturbs the
/// robot, o.best on the nominal robot) over the study's validation set into o's validation
/// fields; `val` is left holding the validation evaluator. Notes its start (`t0`: the study's
/// start) and end, and counts the trial runs between, on opt.progress. The numbers are those
/// of plain evaluate_full calls.
void run_validation(const Study& st, const StudyRunOptions& opt, double t0, StudyOutcome& o,
                    std::optional<Evaluator>& val);

}  // namespace pronk::optimize
