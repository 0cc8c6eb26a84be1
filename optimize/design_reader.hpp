// Reading a design.json of `pronk optimize` as strictly as any input: every key known and of
// its type (io::InputError naming the file, the JSON Pointer, what was expected and what was
// found), and the design consistent with itself: its parameters, scene, study hashes,
// costs, constraints, per-trial decisions and tolerances agree with its unit and with the
// study document it carries.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/objective.hpp"
#include "optimize/reproduction_record.hpp"
#include "optimize/study.hpp"

namespace pronk::optimize {

/// What a design records of one evaluated set (the study's scenarios or its validation set).
struct RecordedSet {
  double cost = 0.0;
  MetricMap metrics;
  /// Per-trial decisions, tolerances and fragile trials: absent in designs recorded
  /// before pronk recorded them.
  std::optional<std::vector<TrialDecision>> trials;
  std::optional<double> cost_tolerance;
  MetricMap tolerances;
  std::vector<long> fragile;
};

struct RecordedDesign {
  Study study;  ///< the study document the design carries, parsed
  std::vector<double> unit;
  RecordedSet scenarios;
  std::optional<RecordedSet> validation;  ///< present exactly when the study has validation
  std::string commit, compiler;
  std::string build_flags;  ///< "" in designs recorded before pronk recorded them
  /// The design records per-trial decisions and tolerances (every design pronk writes now).
  bool has_reproduction_record() const { return scenarios.trials.has_value(); }
};

/// Reads and checks `design` (read from `path`, named in errors; a relative scene path of its
/// study resolves against the path's directory). Throws io::InputError.
RecordedDesign read_design(const nlohmann::json& design, const std::string& path);

/// The first place where `a` and `b` differ, numbers compared to `rtol` relative (and 1e-300
/// absolute), as a JSON Pointer below `pointer`; "" when they agree. With `b_may_omit`, an
/// object key of `a` that `b` lacks is no difference (a key of `b` that `a` lacks still is).
std::string first_json_difference(const nlohmann::json& a, const nlohmann::json& b, double rtol,
                                  const std::string& pointer = "", bool b_may_omit = false);

}  // namespace pronk::optimize
