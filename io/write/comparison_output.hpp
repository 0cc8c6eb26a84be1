// The files of `pronk compare` (several designs run on the same trials), from plain data the
// comparison fills in (optimize/compare_output.hpp): compare.csv (one row per metric, one
// column per design), trials.csv (every trial's outcome for every design), summary.md and
// compare.json (what the designs are, where they came from, which trial is played back; the
// page reads it). Every file is written atomically.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::io {

/// One design: a column of the comparison.
struct ComparisonColumn {
  std::string label;      ///< the column's name: unique, of [A-Za-z0-9_.-]
  std::string file;       ///< its design.json, as given
  std::string study;      ///< the study that tuned it
  std::string scene;      ///< its scene's name
  std::string own_model;  ///< the model its study ran in
  std::string model;      ///< the model it ran in here
  /// Run on its own study's trials, objective and model: its numbers are the ones its
  /// design.json records (on the recording build).
  bool own_study = false;
  std::vector<std::pair<std::string, double>> parameters;  ///< its own, in its study's order
  std::string run_dir;  ///< its playback run, relative to the comparison's directory
};

/// One design's outcome of one trial.
struct ComparisonTrial {
  /// "stabilized", "completed" (not stabilized), "fell", "diverged", or "failed" (the
  /// design's parameters made no valid scene in this model: nothing ran).
  std::string outcome;
  std::map<std::string, double> metrics;
};

/// One set of trials (the study's scenarios, or its validation set) as every design ran it.
struct ComparisonSet {
  std::string name;         ///< "scenarios" or "validation"
  std::string description;  ///< "64 random trials (seed 6402) of 20 s"
  std::vector<std::string> trial_names;
  // Per design, in column order:
  std::vector<std::optional<double>> cost;  ///< the reference study's objective (none: failed)
  std::vector<std::map<std::string, double>> metrics;  ///< aggregated over the trials
  std::vector<std::string> failure;                    ///< "" or why nothing ran
  std::vector<std::vector<ComparisonTrial>> trials;    ///< [design][trial]
};

struct ComparisonData {
  std::string reference_file;   ///< the design whose study's trials every design ran
  std::string reference_study;  ///< its study's name
  std::string model;            ///< the model every design ran in; "" each its own
  bool stability = true;        ///< the spectral radius was computed (else its row is left out)
  std::vector<ComparisonColumn> designs;
  std::vector<ComparisonSet> sets;
  std::string playback_set;  ///< "nominal", "scenarios" or "validation"
  long playback_index = -1;  ///< the trial's index in its set (-1: nominal)
  std::string playback_name;
  std::vector<std::string> notes;  ///< what a reader must know (models differ, ...)
};

/// One row of the side-by-side table: a set's cost or aggregated metric for every design
/// (nothing where a design does not report it). The rows of compare.csv, summary.md and the
/// terminal: an objective term "mean(m)" equal to the row m for every design is left out.
struct ComparisonRow {
  std::string set, metric;
  std::vector<std::optional<double>> values;
};
std::vector<ComparisonRow> comparison_rows(const ComparisonData& c);

/// The per-trial metrics trials.csv shows beside each outcome (those a design reports).
const std::vector<std::string>& comparison_trial_metrics();

std::string comparison_metrics_csv(const ComparisonData& c);  ///< compare.csv
std::string comparison_trials_csv(const ComparisonData& c);   ///< trials.csv
std::string comparison_summary_md(const ComparisonData& c);   ///< summary.md
nlohmann::json comparison_json(const ComparisonData& c);      ///< compare.json

/// Writes compare.csv, trials.csv, summary.md and compare.json into `dir` (created).
void write_comparison_files(const std::string& dir, const ComparisonData& c);

}  // namespace pronk::io
