// Running a robustness map (docs/maps.md): the cells, then the boundary bisection of
// every row, as independent tasks handed to a TaskRunner (threads on one
// machine, or MPI ranks); a JSON-lines journal of finished tasks for --resume;
// the result files written atomically by the one process that owns them.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/map/map_engine.hpp"
#include "optimize/map/map_study.hpp"
#include "optimize/progress.hpp"

namespace pronk::optimize::map {

/// A unit of work: a cell (kind 0, index = cell) or the bisection of a row
/// (kind 1, index = row, between good and bad). Self-contained given the study.
struct MapTask {
  int kind = 0;
  long index = 0;
  double good = 0.0, bad = 0.0;  ///< kind 1: the bracket [axis-0 unit]
};

/// Computes a task: the journal/result record of a cell or of a row's boundary.
nlohmann::json compute_task(const MapStudy& st, const MapTask& task);

/// Distributes tasks over workers. on_result is called once per finished task,
/// on the calling process, never concurrently; tasks may finish in any order.
/// When *stop becomes true no new task starts.
class TaskRunner {
 public:
  virtual ~TaskRunner() = default;
  virtual void run(const MapStudy& st, const std::vector<MapTask>& tasks,
                   const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
                   const std::atomic<bool>* stop) = 0;
  /// "2 threads", "4 MPI ranks", ... for reports.
  virtual std::string describe() const = 0;
};

/// Threads of one process (dynamic scheduling: a worker takes the next task when done).
class LocalRunner final : public TaskRunner {
 public:
  explicit LocalRunner(int threads) : threads_(threads < 1 ? 1 : threads) {}
  void run(const MapStudy& st, const std::vector<MapTask>& tasks,
           const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
           const std::atomic<bool>* stop) override;
  std::string describe() const override;

 private:
  int threads_;
};

struct MapRunOptions {
  int threads = 1;               ///< LocalRunner threads when no runner is given
  TaskRunner* runner = nullptr;  ///< e.g. the MPI runner; nullptr: LocalRunner(threads)
  bool resume = false;           ///< continue from the journal in the output directory
  /// With resume: compute the journal's records again and refuse any that differs: -1 none
  /// (only the last cell, always), 0 every record, N a sample of N (verify_seed).
  long verify = -1;
  std::uint64_t verify_seed = 0;
  std::string out_dir;                           ///< default: the study's
  ProgressStyle progress = ProgressStyle::kOff;  ///< progress on stderr (progress.hpp)
  bool figures = true;  ///< render the SVG heat maps (the .gp scripts are always written)
  const std::atomic<bool>* stop_flag = nullptr;  ///< Ctrl-C: stop after the running tasks
  /// Empty when valid, else which field, its value and the rule.
  std::string validate() const;
};

struct MapOutcome {
  std::string status = "completed";  ///< "completed" or "stopped" (results not written)
  std::string reason;
  std::string out_dir;
  long cells = 0;
  long cells_computed = 0, cells_replayed = 0;  ///< this run / from the journal
  long rows_bisected = 0, bisections_replayed = 0;
  long verified = 0;       ///< journal records computed again (verify)
  long simulations = 0;    ///< trial runs of the whole map (cells and probes)
  double wall_time = 0.0;  ///< [s]
  double cells_time = 0.0, bisection_time = 0.0, output_time = 0.0;  ///< phases of wall_time [s]
  std::vector<CellSummary> summaries;
  std::vector<BoundaryResult> boundaries;
  nlohmann::json summary;  ///< summary.json
};

/// Runs (or resumes) the map and writes cells.csv, trials.csv, boundary.csv,
/// summary.json, fraction.svg and disagreement.svg (with their .gp scripts), holding the
/// output directory's OutputLock. Throws io::InputError for a journal of another study, an
/// edited one (map_journal.hpp), an existing journal without resume, or a directory another
/// run holds; std::runtime_error on I/O failure.
MapOutcome run_map(const MapStudy& st, const MapRunOptions& options);

}  // namespace pronk::optimize::map
