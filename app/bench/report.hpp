// What a `pronk bench` run measured, and its written forms: bench.json (with the provenance
// of the run) and the CSV tables work_precision.csv, fidelity_ladder.csv and
// fidelity_robustness.csv.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/auto_check.hpp"
#include "app/bench/suite.hpp"

namespace pronk::app::bench {

/// Everything the suites and peers measured, in the order they ran.
struct BenchResults {
  std::vector<WorkPoint> sat, sweep, hop;
  std::vector<OrderFit> orders;
  std::vector<FidelityPoint> ladder;
  LadderRobustness robustness;
  nlohmann::json drop;
  std::vector<AutoCheck> autos;
  nlohmann::json cvode, mujoco;
  bool peer_failed = false;
};

/// v as "%.6g" (the CSV tables, the figures' data and the printed summary).
std::string fmt(double v);

/// The rows of bench.json.
nlohmann::json to_json(const WorkPoint& p);
nlohmann::json to_json(const FidelityPoint& p);
nlohmann::json to_json(const LadderRobustness& lr);
/// bench.json's "auto_check": per scene auto against the fastest run at the same accuracy.
nlohmann::json auto_check_json(const std::vector<AutoCheck>& autos);

/// The run's date (UTC, ISO 8601) and machine (CPU model, hardware threads).
std::string now_utc();
std::string machine();

/// bench.json without its total wall time; `all` the work-precision points of every problem.
nlohmann::json bench_document(const BenchConfig& c, const BenchResults& r,
                              const std::vector<WorkPoint>& all);

/// The CSV tables.
std::string work_precision_csv(const std::vector<WorkPoint>& pts);
std::string ladder_csv(const std::vector<FidelityPoint>& pts);
std::string robustness_csv(const LadderRobustness& lr);

}  // namespace pronk::app::bench
