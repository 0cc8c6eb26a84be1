// The objective API (docs/studies.md): evaluate(parameters) -> Evaluation over a
// scene, a scenario set, objective terms and constraints. A pure function of
// its inputs: thread-safe, deterministic whatever the thread count; the
// scenario runs of one evaluation go in parallel.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/job_farm.hpp"
#include "optimize/job_schedule.hpp"
#include "optimize/objective.hpp"
#include "optimize/parameters.hpp"
#include "optimize/problem.hpp"
#include "optimize/scenario.hpp"
#include "optimize/thread_pool.hpp"
#include "sim/reduced/stride_map.hpp"

namespace pronk::optimize {

/// One objective of a multi-objective study: a name and its weighted terms (summed as the
/// single "objective" of other studies is).
struct NamedObjective {
  std::string name;
  std::vector<ObjectiveTerm> terms;
};

/// Everything an evaluation depends on (immutable once built).
struct EvaluatorConfig {
  nlohmann::json scene_doc;          ///< the scene document parameters are bound into
  std::string scene_file = "scene";  ///< names the scene in error messages
  std::vector<Parameter> parameters;
  ScenarioSet scenarios;
  std::vector<ObjectiveTerm> objective;  ///< empty in a multi-objective study (cost 0)
  /// A multi-objective study's objectives (docs/pareto.md), each minimized; empty otherwise.
  std::vector<NamedObjective> objectives;
  std::vector<ConstraintSpec> constraints;  ///< each has exactly one of max / min
  bool stability = true;                    ///< compute the spectral radius of the stride map
  double fall_penalty = 1.0;  ///< error metrics of a fallen run are at least this [m or rad]
  double failure_cost = 1e6;  ///< cost (and constraint value) of an evaluation that failed
  reduced::SettleCriteria settle;
  int threads = 1;  ///< worker threads for the scenario runs
  /// Where the scenario runs go instead (MPI ranks); nullptr: the threads above.
  /// Not part of what an evaluation computes: the numbers are the same either way.
  JobFarm* farm = nullptr;
};

/// One scenario's outcome.
struct ScenarioOutcome {
  std::string name;
  std::string status;  ///< "completed", "fell", "diverged"
  std::string reason;
  MetricMap metrics;
  long strides = 0;
};

/// One job of an evaluation: job 0 is the stability analysis, job i > 0 runs
/// scenario i - 1.
struct JobOutcome {
  std::string error;  ///< non-empty: the job threw (an internal error)
  StabilityEstimate stability;
  ScenarioOutcome scenario;
};

/// One evaluation.
struct Evaluation {
  bool ok = true;       ///< false: these parameters make an invalid scene, or an internal error
  std::string failure;  ///< why, when !ok
  std::vector<double> unit;    ///< optimizer coordinates
  std::vector<double> values;  ///< physical parameter values
  double cost = 0.0;
  /// One value per EvaluatorConfig::objectives (failure_cost each when !ok); empty in a
  /// single-objective study.
  std::vector<double> objectives;
  std::vector<double> constraints;  ///< g_j <= 0 feasible
  MetricMap aggregated;  ///< mean of every metric, plus every objective/constraint aggregate
  std::vector<ScenarioOutcome> scenarios;
  double spectral_radius = 0.0;
  std::string stability_reason;  ///< why no orbit was found, if so
  /// How the spectral radius was obtained (StabilityEstimate::method); "" without one.
  std::string stability_method;
  scene::ModelKind model = scene::ModelKind::kImpulse;  ///< the model the scenarios ran in
  long simulations = 0;                                 ///< scenario runs + stride-map runs
  long strides = 0;                                     ///< simulated strides
  double wall_time = 0.0;                               ///< [s]
  double binding_time = 0.0;  ///< [s] spent binding parameters and building the scene
};

class Evaluator final : public Problem {
 public:
  explicit Evaluator(EvaluatorConfig config);

  /// The full evaluation at optimizer coordinates `unit` (each in [0, 1]).
  Evaluation evaluate_full(const std::vector<double>& unit) const;
  /// The same, calling `on_trial` (from whichever worker thread ran it: it must be
  /// thread-safe and must not throw) as each scenario run ends, for progress. On a farm the
  /// runs are remote and `on_trial` is not called.
  Evaluation evaluate_full(const std::vector<double>& unit,
                           const std::function<void()>& on_trial) const;
  /// Full evaluations of several points, in parallel over the points (each
  /// point's scenarios serial); the same numbers as evaluate_full.
  std::vector<Evaluation> evaluate_full_batch(const std::vector<std::vector<double>>& xs) const;
  /// The scene a parameter vector produces (throws io::InputError when invalid).
  scene::Scene scene_at(const std::vector<double>& unit) const;

  // Problem:
  int dimension() const override { return static_cast<int>(config_.parameters.size()); }
  int num_constraints() const override { return static_cast<int>(config_.constraints.size()); }
  std::vector<double> lower_bounds() const override;
  std::vector<double> upper_bounds() const override;
  std::vector<double> initial_point() const override;
  std::vector<std::string> variable_names() const override;
  std::vector<std::string> constraint_names() const override;
  ProblemEvaluation evaluate(const std::vector<double>& x) const override;
  std::vector<ProblemEvaluation> evaluate_batch(
      const std::vector<std::vector<double>>& xs) const override;

  const EvaluatorConfig& config() const { return config_; }
  static ProblemEvaluation to_problem(const Evaluation& e);

  /// A job given as {job, unit...}, answered as JSON (evaluator_wire.hpp): what a
  /// JobFarm computes, here or on another rank.
  nlohmann::json compute_job(const std::vector<double>& job) const;

 private:
  Evaluation evaluate_impl(const std::vector<double>& unit, bool parallel,
                           const std::function<void()>* on_trial = nullptr) const;
  /// Binds the parameters; false (and ev failed) when they make no valid scene.
  bool bind(const std::vector<double>& unit, Evaluation& ev, scene::Scene& base) const;
  JobOutcome run_job(const scene::Scene& base, long job) const;
  /// The evaluation from its jobs' outcomes: aggregation, objective, constraints.
  void finish(Evaluation& ev, const scene::Scene& base, std::vector<JobOutcome>& jobs) const;
  /// Every point's jobs on the farm at once.
  std::vector<Evaluation> evaluate_on_farm(const std::vector<std::vector<double>>& xs) const;
  long farm_id_ = -1;
  EvaluatorConfig config_;
  std::unique_ptr<ThreadPool> pool_;
  /// Longest-first start order of an evaluation's jobs (the schedule only, not the numbers).
  std::unique_ptr<JobSchedule> schedule_ = std::make_unique<JobSchedule>();
  /// Fast binding: when every parameter names a plain number field of the
  /// scene whose validity rule its bounds already satisfy, parameters are
  /// written straight into a copy of the parsed scene (no JSON round trip).
  bool fast_binding_ = false;
  scene::Scene base_scene_;
};

}  // namespace pronk::optimize
