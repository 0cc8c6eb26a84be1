// Multi-objective studies (docs/pareto.md): a study with "objectives" and a pagmo
// multi-objective algorithm (nsga2, moead, nspso) run through optimize/pareto/moo_driver over
// the study's Evaluator, each batch of the driver one batch of evaluations (threads or MPI
// ranks), journaled and resumable like the other libraries. Writes pareto.csv and pareto.json.
//
// Constraints. pagmo 2.18's multi-objective algorithms are unconstrained. The driver sees
// every objective plus the quadratic penalty of the single-objective pagmo path,
// penalty_weight * sum_j max(g_j, 0)^2 (the same for every objective; 0 for a feasible
// design), so infeasible designs are pushed back but still ranked. The reported front holds
// only feasible designs (ok, every g_j <= 1e-8): the non-dominated set, on the unpenalized
// objectives, of every feasible evaluation of the run. The hypervolume per generation is the
// driver's, of its archive of penalized objective vectors (for feasible designs the same
// numbers).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/pareto/moo_driver.hpp"
#include "optimize/reproduce.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"

namespace pronk::optimize {

/// One design of the reported front.
struct FrontDesign {
  long evaluation = 0;  ///< its index among the run's evaluations (the journal's "index")
  Evaluation scenarios;  ///< re-evaluated on the study's scenarios (the recorded numbers)
  std::optional<Evaluation> validation;  ///< on the validation set, when the study has one
  /// Its perturbation run (reproduction_record.hpp), as design.json records one: the
  /// tolerance of every metric, objective and constraint value, and the fragile trials, of
  /// each set. What `pronk reproduce --front-index` uses on another build.
  nlohmann::json reproduction;
};

struct MooStudyOutcome {
  pareto::MooResult result;        ///< the driver's (penalized objectives)
  std::vector<FrontDesign> front;  ///< the feasible non-dominated designs, by evaluation index
  long knee = -1;                  ///< pareto::knee of the front, an index into `front`
  double front_hypervolume = 0.0;  ///< of the front against result.reference
  long evaluations = 0;
  long feasible = 0;  ///< evaluations that are ok and satisfy every constraint
  long failed = 0;    ///< evaluations with ok == false
  long replayed = 0;  ///< evaluations answered from the journal on --resume
  long verified = 0;  ///< journal records evaluated again (--verify)
  bool stopped = false;  ///< Ctrl-C: the journal holds what was done; no pareto files written
  std::string out_dir;
  double wall_time = 0.0;  ///< [s]
};

/// The penalty the driver adds to every objective: weight * sum_j max(g_j, 0)^2.
double constraint_penalty(const std::vector<double>& constraints, double weight);

/// Runs a multi-objective study (study.moo set), holding the output directory's lock, and
/// writes OUT/pareto.csv and OUT/pareto.json atomically. Throws io::InputError for a journal
/// of another study or an edited one, an existing journal without --resume, a directory
/// another run holds; std::runtime_error for I/O failures.
MooStudyOutcome run_moo_study(const Study& study, const StudyRunOptions& options);

/// pareto.json of a finished run (self-contained: its study document inlines the scene).
nlohmann::json pareto_document(const Study& study, const MooStudyOutcome& outcome, int threads);

/// pareto.csv: one row per front design.
std::string pareto_csv(const Study& study, const MooStudyOutcome& outcome);

/// Re-evaluates front design `index` of pareto.json `pareto` (read from `path`) and compares
/// its recorded objectives, constraints, metrics (and validation metrics) by the rules of
/// reproduce_design: bit for bit on the recording build (or with options.strict on its
/// compiler and flags), within options.rtol when given, else within the tolerances the
/// design's perturbation run recorded; the per-trial decisions must be identical except
/// for the trials that run found fragile. Throws io::InputError for a document that is not
/// a pareto.json or an index out of range.
ReproduceReport reproduce_front_design(const nlohmann::json& pareto, const std::string& path,
                                       long index, const ReproduceOptions& options);

}  // namespace pronk::optimize
