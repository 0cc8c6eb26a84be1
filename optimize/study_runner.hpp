// Runs a study end to end: journal (resumable), optimizer, result files
// (design.json, history.csv, summary.md, figures) written atomically.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "optimize/journal.hpp"
#include "optimize/progress.hpp"
#include "optimize/study.hpp"

namespace pronk::optimize {

struct StudyRunOptions {
  int threads = 1;
  bool resume = false;  ///< continue from the journal in the output directory
  /// With resume: evaluate the journal's records again and refuse any that differs: -1
  /// none (only the last record, always), 0 every record, N a sample of N (verify_seed).
  long verify = -1;
  std::uint64_t verify_seed = 0;
  std::string out_dir;                           ///< overrides the study's output directory
  ProgressStyle progress = ProgressStyle::kOff;  ///< progress on stderr (progress.hpp)
  const std::atomic<bool>* stop_flag = nullptr;  ///< Ctrl-C
  /// The evaluations' scenario runs on other processes (MPI ranks); nullptr: threads.
  JobFarm* farm = nullptr;
};

struct StudyOutcome {
  OptimizerResult result;
  Evaluation initial;  ///< the starting design
  Evaluation best;     ///< the tuned design
  std::string out_dir;
  bool validated = false;         ///< the study has a validation set
  Evaluation validation_initial;  ///< the starting design on the validation set
  Evaluation validation_best;     ///< the tuned design on the validation set
  /// The validation set perturbs the robot (and "compare_nominal"): the tuned design on the
  /// same starts with the nominal robot, reported beside validation_best.
  bool validation_compared = false;
  Evaluation validation_nominal;
  /// The design's per-trial tolerances and fragile trials (record_reproduction).
  nlohmann::json reproduction;
  long replayed = 0;       ///< evaluations taken from the journal on --resume
  long verified = 0;       ///< journal records evaluated again (verify)
  double wall_time = 0.0;  ///< [s]
};

/// Runs the study, holding the output directory's OutputLock. Throws io::InputError for a
/// journal of another study, an edited one (see journal.hpp, journal_check.hpp), an
/// existing journal without --resume, or a directory another run holds;
/// std::runtime_error for I/O failures.
StudyOutcome run_study(const Study& study, const StudyRunOptions& options);

/// The first line of a study's journal: its name, hash, parameters, constraints, optimizer
/// ("library:algorithm") and seed.
nlohmann::json journal_header(const Study& study, const Evaluator& ev);

/// The journal at `path` to resume, checked against the study (its hash, its last record, and
/// with options.verify its records re-evaluated: *verified of them); nothing when there is
/// none (or only a torn header). An existing journal without --resume is bad input
/// (io::InputError).
JournalContents resumable_journal(const std::string& path, const Study& study,
                                  const Evaluator& ev, const StudyRunOptions& options,
                                  long* verified);

/// The compiler that built this binary ("gcc 12.2.0", ...), recorded in designs.
std::string compiler_id();

/// The evaluator of the study's validation set (same scene and parameters).
Evaluator validation_evaluator(const Study& study, int threads, JobFarm* farm = nullptr);

/// design.json of a finished study (self-contained: reproducible from it alone).
nlohmann::json design_document(const Study& study, const StudyOutcome& outcome, int threads);

/// The metric rows ("| name | a | b |") of a summary table of two evaluations, as
/// report.html shows them: an objective term "mean(m)" that repeats the row m is left out,
/// and so is the spectral radius when the study did not compute it (`stability` false: it
/// reads 0, which would look perfect).
std::string metric_rows(const MetricMap& a, const MetricMap& b, bool stability);

/// Simulates design `x` (optimizer coordinates) on the evaluator's first scenario and writes
/// its run (CSV, figures) into `dir`: the playback of a tuned or front design.
void write_design_run(const std::string& dir, const Evaluator& ev, const std::vector<double>& x);

}  // namespace pronk::optimize
