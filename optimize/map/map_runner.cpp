#include "optimize/map/map_runner.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/figure_batch.hpp"
#include "optimize/journal.hpp"
#include "optimize/map/map_journal.hpp"
#include "optimize/map/map_output.hpp"
#include "optimize/output_lock.hpp"
#include "optimize/progress.hpp"
#include "optimize/thread_pool.hpp"

namespace pronk::optimize::map {

using nlohmann::json;

json compute_task(const MapStudy& st, const MapTask& task) {
  if (task.kind == 0) {
    json j = to_json(compute_cell(st, task.index));
    j["task"] = "cell";
    return j;
  }
  BoundaryResult b;
  b.row = task.index;
  b.status = "bisected";
  b.good = b.boundary = task.good;
  b.bad = task.bad;
  json j = to_json(bisect_row(st, b));
  j["task"] = "boundary";
  return j;
}

void LocalRunner::run(const MapStudy& st, const std::vector<MapTask>& tasks,
                      const std::function<void(const MapTask&, const json&)>& on_result,
                      const std::atomic<bool>* stop) {
  ThreadPool pool(threads_);
  std::mutex mu;
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  pool.parallel_for(static_cast<long>(tasks.size()), [&](long i) {
    if ((stop && stop->load()) || failed.load()) return;
    try {
      const json r = compute_task(st, tasks[static_cast<size_t>(i)]);
      std::lock_guard<std::mutex> lock(mu);
      on_result(tasks[static_cast<size_t>(i)], r);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mu);
      if (!error) error = std::current_exception();
      failed.store(true);
    }
  });
  if (error) std::rethrow_exception(error);
}

std::string LocalRunner::describe() const {
  return std::to_string(threads_) + (threads_ == 1 ? " thread" : " threads");
}

std::string MapRunOptions::validate() const {
  if (threads < 1) return "threads = " + std::to_string(threads) + ": must be >= 1";
  return "";
}

namespace {

/// The progress of a map on stderr (progress.hpp), one count per phase (cells, then the
/// boundary rows' bisection).
class MapProgress {
 public:
  MapProgress(const MapStudy& st, const MapRunOptions& options) : st_(st), options_(options) {}
  void operator()(const char* what, long n, long total) {
    if (!line_ || phase_ != what) {
      if (line_) line_->finish();
      phase_ = what;
      line_ = std::make_unique<Progress>(options_.progress, "map " + st_.name + ": " + what, total);
    }
    line_->update(n);
    if (n >= total) line_->finish();
  }

 private:
  const MapStudy& st_;
  const MapRunOptions& options_;
  std::string phase_;
  std::unique_ptr<Progress> line_;
};

/// The run's shared state: the study, its options, the runner, the journal.
struct MapRun {
  const MapStudy& st;
  const MapRunOptions& options;
  TaskRunner& runner;
  JournalWriter& journal;
  MapProgress& progress;
  double t0;
};

/// The journal to resume, checked (and verified with options.verify: out->verified); none
/// when there is none (or only a torn header). An existing one without --resume is refused.
MapJournalState resumable_map_journal(const std::string& path, const MapStudy& st,
                                      const MapRunOptions& options, TaskRunner& runner,
                                      MapOutcome* out) {
  MapJournalState js = read_map_journal(path, st);
  if (!js.exists) return {};
  if (!options.resume) {
    throw io::InputError(path, "",
                         "no journal (pass --resume to continue it, or choose another --out)",
                         "the journal of an earlier run");
  }
  out->verified = verify_map_journal(js, st, runner, options.verify, options.verify_seed, path);
  return js;
}

/// Hands the runner's results on in task order, whatever order the workers finish them in:
/// a result waits until every earlier task's result has been handed on, so the journal is
/// the same bytes for any thread or rank count, and a resumed map writes the records an
/// uninterrupted one does. A result still waiting when the map stops is computed again on
/// --resume.
class InTaskOrder {
 public:
  InTaskOrder(const std::vector<MapTask>& tasks,
              std::function<void(const MapTask&, const json&)> deliver)
      : tasks_(tasks), deliver_(std::move(deliver)) {}
  void operator()(const MapTask& task, const json& r) {
    waiting_.emplace(static_cast<size_t>(&task - tasks_.data()), r);
    for (auto it = waiting_.find(next_); it != waiting_.end(); it = waiting_.find(next_)) {
      deliver_(tasks_[next_], it->second);
      waiting_.erase(it);
      ++next_;
    }
  }

 private:
  const std::vector<MapTask>& tasks_;
  std::function<void(const MapTask&, const json&)> deliver_;
  std::map<size_t, json> waiting_;
  size_t next_ = 0;
};

/// Phase 1: the cells not in the journal. Returns false when stopped (out says why).
bool run_map_cells(const MapRun& run, MapJournalState& js, std::vector<CellResult>* cells,
                   MapOutcome* out) {
  const MapStudy& st = run.st;
  std::vector<bool> have(cells->size(), false);
  std::vector<MapTask> tasks;
  for (long i = 0; i < st.cells(); ++i) {
    auto it = js.cells.find(i);
    if (it != js.cells.end()) {
      (*cells)[static_cast<size_t>(i)] = std::move(it->second);
      have[static_cast<size_t>(i)] = true;
      ++out->cells_replayed;
    } else {
      tasks.push_back({0, i, 0.0, 0.0});
    }
  }
  long done = out->cells_replayed;
  const double t_cells = monotonic_seconds();
  run.runner.run(st, tasks,
                 InTaskOrder(tasks,
                             [&](const MapTask& task, const json& r) {
                               run.journal.append(r);
                               (*cells)[static_cast<size_t>(task.index)] = cell_from_json(r);
                               have[static_cast<size_t>(task.index)] = true;
                               ++out->cells_computed;
                               run.progress("cells", ++done, st.cells());
                             }),
                 run.options.stop_flag);
  for (bool h : have) {
    if (!h) {
      out->status = "stopped";
      out->reason = "interrupted after " + std::to_string(done) + " of " +
                    std::to_string(st.cells()) + " cells (journal kept; --resume continues)";
      out->wall_time = monotonic_seconds() - run.t0;
      return false;
    }
  }
  out->cells_time = monotonic_seconds() - t_cells;
  return true;
}

/// Phase 2: the boundary of every row, bisected where a good cell is followed by a bad one.
/// Returns false when stopped (out says why).
bool run_map_boundaries(const MapRun& run, const MapJournalState& js, MapOutcome* out) {
  const MapStudy& st = run.st;
  out->boundaries.resize(static_cast<size_t>(st.rows()));
  std::vector<bool> have_b(out->boundaries.size(), false);
  std::vector<MapTask> tasks;
  for (long r = 0; r < st.rows(); ++r) {
    const BoundaryResult b = initial_bracket(st, out->summaries, r);
    auto it = js.boundaries.find(r);
    if (b.status != "bisected") {
      out->boundaries[static_cast<size_t>(r)] = b;
      have_b[static_cast<size_t>(r)] = true;
    } else if (it != js.boundaries.end()) {
      out->boundaries[static_cast<size_t>(r)] = it->second;
      have_b[static_cast<size_t>(r)] = true;
      ++out->bisections_replayed;
    } else {
      tasks.push_back({1, r, b.good, b.bad});
    }
  }
  long bdone = 0;
  const double t_bisect = monotonic_seconds();
  run.runner.run(
      st, tasks,
      InTaskOrder(tasks,
                  [&](const MapTask& task, const json& r) {
                    run.journal.append(r);
                    out->boundaries[static_cast<size_t>(task.index)] = boundary_from_json(r);
                    have_b[static_cast<size_t>(task.index)] = true;
                    ++out->rows_bisected;
                    run.progress("boundary rows", ++bdone, static_cast<long>(tasks.size()));
                  }),
      run.options.stop_flag);
  out->bisection_time = monotonic_seconds() - t_bisect;
  // The lower edge comes from the cells (not journaled).
  for (long r = 0; r < st.rows(); ++r)
    out->boundaries[static_cast<size_t>(r)].first_good =
        initial_bracket(st, out->summaries, r).first_good;
  for (bool h : have_b) {
    if (!h) {
      out->status = "stopped";
      out->reason = "interrupted during the boundary bisection (journal kept; --resume continues)";
      out->wall_time = monotonic_seconds() - run.t0;
      return false;
    }
  }
  return true;
}

/// summary.json, the CSVs and the heat maps.
void write_map_outputs(const MapStudy& st, const MapRunOptions& options,
                       const std::vector<CellResult>& cells, MapOutcome* outcome) {
  MapOutcome& out = *outcome;
  out.summary = summary_json(st, out.summaries, out.boundaries);
  out.simulations = out.summary["totals"]["simulations"].get<long>();
  // The files are independent: written at once, so their fsyncs and the two
  // gnuplot runs (their data inline in the scripts) overlap (the serial tail of the map,
  // which no worker shortens).
  io::FigureBatch figures;
  for (const char* what : {"fraction", "disagreement"}) {
    const std::string script = heatmap_script(st, out.summaries, out.boundaries, what);
    if (options.figures)
      figures.add(out.out_dir, what, script);
    else
      io::write_file_atomic(out.out_dir + "/" + what + ".gp", script);
  }
  figures.start();
  std::vector<std::future<void>> writes;
  auto write = [&writes](std::function<void()> job) {
    writes.push_back(std::async(std::launch::async, std::move(job)));
  };
  write([&] { io::write_file_atomic(out.out_dir + "/cells.csv", cells_csv(st, out.summaries)); });
  write([&] { io::write_file_atomic(out.out_dir + "/trials.csv", trials_csv(st, cells)); });
  write([&] {
    io::write_file_atomic(out.out_dir + "/boundary.csv",
                          boundary_csv(st, out.summaries, out.boundaries));
  });
  write([&] { io::write_file_atomic(out.out_dir + "/summary.json", out.summary.dump(2) + "\n"); });
  for (auto& w : writes) w.get();  // the first failure is rethrown (after all ended)
  figures.finish();
}

}  // namespace

MapOutcome run_map(const MapStudy& st, const MapRunOptions& options) {
  const std::string bad = options.validate();
  if (!bad.empty()) throw std::invalid_argument("MapRunOptions: " + bad);
  const double t0 = monotonic_seconds();
  LocalRunner local(options.threads);
  TaskRunner& runner = options.runner ? *options.runner : local;
  MapOutcome out;
  out.out_dir = options.out_dir.empty() ? st.output_dir : options.out_dir;
  out.cells = st.cells();
  io::make_directories(out.out_dir);
  const OutputLock lock(out.out_dir, "pronk map");
  remove_stale_temporaries(out.out_dir, 0);
  const std::string journal_path = out.out_dir + "/journal.jsonl";
  MapJournalState js = resumable_map_journal(journal_path, st, options, runner, &out);
  // fsynced at most every half second and at the end: a cell is a few milliseconds of work,
  // an fsync about 6 ms (a power cut loses at most that much, which --resume recomputes).
  JournalWriter journal(journal_path, map_journal_header(st),
                        js.exists ? prepare_for_append(journal_path, js.end) : "", 0.5);
  MapProgress progress(st, options);
  const MapRun run{st, options, runner, journal, progress, t0};

  std::vector<CellResult> cells(static_cast<size_t>(st.cells()));
  if (!run_map_cells(run, js, &cells, &out)) return out;
  out.summaries = summarize(st, cells);
  if (!run_map_boundaries(run, js, &out)) return out;
  journal.sync();

  const double t_out = monotonic_seconds();
  write_map_outputs(st, options, cells, &out);
  out.output_time = monotonic_seconds() - t_out;
  out.wall_time = monotonic_seconds() - t0;
  return out;
}

}  // namespace pronk::optimize::map
