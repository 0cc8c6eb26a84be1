// An evaluator's configuration and its jobs' outcomes as JSON, for evaluations
// spread over processes (optimize/job_farm.hpp). Doubles travel exactly
// (shortest round-trip text; non-finite values as "inf", "-inf", "nan"), so a job
// computed on another rank gives the same bits as one computed here.
#pragma once

#include <nlohmann/json.hpp>

#include "optimize/evaluator.hpp"

namespace pronk::optimize {

/// What a job needs of a configuration: the scene document, the parameters, the
/// scenarios and the metric settings (not the objective, the constraints or the
/// farm: those stay with the process that aggregates).
nlohmann::json evaluator_config_to_wire(const EvaluatorConfig& config);
/// The configuration back (one thread, no farm). Throws std::runtime_error on a
/// malformed document.
EvaluatorConfig evaluator_config_from_wire(const nlohmann::json& wire);

nlohmann::json job_outcome_to_wire(const JobOutcome& outcome);
JobOutcome job_outcome_from_wire(const nlohmann::json& wire);

}  // namespace pronk::optimize
