#include "optimize/map/map_runner.hpp"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <map>
#include <mutex>

#include "optimize/journal.hpp"
#include "optimize/map/map_output.hpp"
#include "optimize/thread_pool.hpp"
#include "io/write/atomic_file.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/write/plot.hpp"

namespace pronk::optimize::map {

using nlohmann::json;

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// What a journal holds: finished cells and bisected rows.
struct JournalState {
  std::map<long, CellResult> cells;
  std::map<long, BoundaryResult> boundaries;
  nlohmann::json last_cell;  ///< the last cell record read (null when none)
  long last_cell_line = 0;
};

// Reads the journal of a map; a torn last line is dropped (and cut from the
// file so appends start on a fresh line). A journal of another study is bad input.
JournalState read_map_journal(const std::string& path, const MapStudy& st) {
  JournalState js;
  std::ifstream in(path, std::ios::binary);
  if (!in) return js;
  std::string line;
  long lineno = 0;
  std::uintmax_t good_bytes = 0, offset = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const bool complete = !in.eof();  // a last line without '\n' is torn
    offset += line.size() + (complete ? 1 : 0);
    json j;
    try {
      if (!complete) throw std::runtime_error("no end of line");
      j = io::parse_json_text(line, path);
    } catch (const std::exception& e) {
      if (in.peek() == std::ifstream::traits_type::eof()) break;  // torn tail
      throw io::InputError(path, "line " + std::to_string(lineno), "a journal record", e.what());
    }
    good_bytes = offset;
    check_seal(j, path, lineno);
    if (lineno == 1) {
      if (j.value("type", "") != "pronk_map_journal" || j.value("hash", "") != st.hash) {
        throw io::InputError(path, "/hash", "the journal of this map study (hash " + st.hash + ")",
                             j.contains("hash") ? io::describe(j.at("hash")) : "no hash");
      }
      continue;
    }
    try {
      const std::string task = j.at("task").get<std::string>();
      if (task == "cell") {
        CellResult c = cell_from_json(j);
        if (c.index < 0 || c.index >= st.cells() || c.trials.size() != st.models.size())
          throw std::runtime_error("cell record does not fit the study");
        js.cells[c.index] = std::move(c);
        js.last_cell = j;
        js.last_cell_line = lineno;
      } else if (task == "boundary") {
        BoundaryResult b = boundary_from_json(j);
        js.boundaries[b.row] = b;
      }
    } catch (const std::exception& e) {
      throw io::InputError(path, "line " + std::to_string(lineno), "a map journal record",
                           e.what());
    }
  }
  in.close();
  if (good_bytes < std::filesystem::file_size(path)) std::filesystem::resize_file(path, good_bytes);
  return js;
}

// Cells are deterministic: the journal's last cell, computed again, must give the same
// bytes, or the journal was not written by this study on this build.
void check_last_cell(const JournalState& js, const MapStudy& st, const std::string& path) {
  if (js.last_cell.is_null()) return;
  json recorded = js.last_cell;
  recorded.erase("checksum");
  const long index = recorded.at("cell").get<long>();
  const json again = compute_task(st, MapTask{0, index, 0.0, 0.0});
  if (again.dump() == recorded.dump()) return;
  throw io::InputError(path, "line " + std::to_string(js.last_cell_line),
                       "the record its re-computation gives (cells are deterministic; a journal "
                       "edited or written by another build cannot be resumed)",
                       "a different record for cell " + std::to_string(index));
}

// The map journal: one JSON line per finished task, flushed to the OS at once
// (an interrupted or killed process loses nothing) and fsynced at most every
// half second and at the end (a power cut loses at most that much, which
// --resume recomputes). A cell is a few milliseconds of work, an fsync here
// about 6 ms: syncing every record would cost more than the map.
class MapJournal {
 public:
  MapJournal(const std::string& path, const json& header) : path_(path) {
    std::error_code ec;
    const bool empty =
        !std::filesystem::exists(path, ec) || std::filesystem::file_size(path, ec) == 0;
    file_ = std::fopen(path.c_str(), "a");
    if (!file_)
      throw std::runtime_error("cannot open journal " + path + ": " + std::strerror(errno));
    if (empty) {
      append(header);
      sync();
    }
  }
  ~MapJournal() {
    try {
      sync();
    } catch (...) {
    }
    std::fclose(file_);
  }
  MapJournal(const MapJournal&) = delete;
  MapJournal& operator=(const MapJournal&) = delete;
  void append(const json& record) {
    const std::string text = sealed(record).dump() + "\n";
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
      throw std::runtime_error("cannot write journal " + path_ + ": " + std::strerror(errno));
    if (now_s() - last_sync_ > 0.5) sync();
  }
  void sync() {
    if (::fsync(fileno(file_)) != 0)
      throw std::runtime_error("cannot sync journal " + path_ + ": " + std::strerror(errno));
    last_sync_ = now_s();
  }

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  double last_sync_ = 0.0;
};

}  // namespace

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

/// The progress line of a map on stderr, at most every 0.2 s (and at the end of a phase).
class MapProgress {
 public:
  MapProgress(const MapStudy& st, const MapRunOptions& options, double t0)
      : st_(st), options_(options), t0_(t0) {}
  void operator()(const char* what, long n, long total) {
    if (!options_.progress) return;
    const double t = now_s();
    if (t - last_print_ < 0.2 && n < total) return;
    last_print_ = t;
    std::fprintf(stderr, "\rmap %s: %s %ld/%ld (%.0f s)", st_.name.c_str(), what, n, total,
                 t - t0_);
    if (n >= total) std::fprintf(stderr, "\n");
  }

 private:
  const MapStudy& st_;
  const MapRunOptions& options_;
  double t0_;
  double last_print_ = 0.0;
};

/// The run's shared state: the study, its options, the runner, the journal.
struct MapRun {
  const MapStudy& st;
  const MapRunOptions& options;
  TaskRunner& runner;
  MapJournal& journal;
  MapProgress& progress;
  double t0;
};

/// Phase 1: the cells not in the journal. Returns false when stopped (out says why).
bool run_map_cells(const MapRun& run, JournalState& js, std::vector<CellResult>* cells,
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
  const double t_cells = now_s();
  run.runner.run(
      st, tasks,
      [&](const MapTask& task, const json& r) {
        run.journal.append(r);
        (*cells)[static_cast<size_t>(task.index)] = cell_from_json(r);
        have[static_cast<size_t>(task.index)] = true;
        ++out->cells_computed;
        run.progress("cells", ++done, st.cells());
      },
      run.options.stop_flag);
  for (bool h : have) {
    if (!h) {
      out->status = "stopped";
      out->reason = "interrupted after " + std::to_string(done) + " of " +
                    std::to_string(st.cells()) + " cells (journal kept; --resume continues)";
      out->wall_time = now_s() - run.t0;
      return false;
    }
  }
  out->cells_time = now_s() - t_cells;
  return true;
}

/// Phase 2: the boundary of every row, bisected where a good cell is followed by a bad one.
/// Returns false when stopped (out says why).
bool run_map_boundaries(const MapRun& run, const JournalState& js, MapOutcome* out) {
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
  const double t_bisect = now_s();
  run.runner.run(
      st, tasks,
      [&](const MapTask& task, const json& r) {
        run.journal.append(r);
        out->boundaries[static_cast<size_t>(task.index)] = boundary_from_json(r);
        have_b[static_cast<size_t>(task.index)] = true;
        ++out->rows_bisected;
        run.progress("boundary rows", ++bdone, static_cast<long>(tasks.size()));
      },
      run.options.stop_flag);
  out->bisection_time = now_s() - t_bisect;
  // The lower edge comes from the cells (not journaled).
  for (long r = 0; r < st.rows(); ++r)
    out->boundaries[static_cast<size_t>(r)].first_good =
        initial_bracket(st, out->summaries, r).first_good;
  for (bool h : have_b) {
    if (!h) {
      out->status = "stopped";
      out->reason = "interrupted during the boundary bisection (journal kept; --resume continues)";
      out->wall_time = now_s() - run.t0;
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
  // gnuplot runs overlap (the serial tail of the map, which no worker shortens).
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
  for (const char* what : {"fraction", "disagreement"}) {
    write([&, what] {
      const std::string script = heatmap_script(st, out.summaries, out.boundaries, what);
      if (options.figures)
        io::render_figure(out.out_dir, what, script);
      else
        io::write_file_atomic(out.out_dir + "/" + what + ".gp", script);
    });
  }
  for (auto& w : writes) w.get();  // the first failure is rethrown (after all ended)
}

}  // namespace

MapOutcome run_map(const MapStudy& st, const MapRunOptions& options) {
  const std::string bad = options.validate();
  if (!bad.empty()) throw std::invalid_argument("MapRunOptions: " + bad);
  const double t0 = now_s();
  LocalRunner local(options.threads);
  TaskRunner& runner = options.runner ? *options.runner : local;
  MapOutcome out;
  out.out_dir = options.out_dir.empty() ? st.output_dir : options.out_dir;
  out.cells = st.cells();
  io::make_directories(out.out_dir);
  const std::string journal_path = out.out_dir + "/journal.jsonl";
  JournalState js;
  if (options.resume) {
    js = read_map_journal(journal_path, st);
    check_last_cell(js, st, journal_path);
  } else {
    std::error_code ec;
    std::filesystem::remove(journal_path, ec);
  }
  MapJournal journal(journal_path,
                     json{{"type", "pronk_map_journal"}, {"name", st.name}, {"hash", st.hash}});
  MapProgress progress(st, options, t0);
  const MapRun run{st, options, runner, journal, progress, t0};

  std::vector<CellResult> cells(static_cast<size_t>(st.cells()));
  if (!run_map_cells(run, js, &cells, &out)) return out;
  out.summaries = summarize(st, cells);
  if (!run_map_boundaries(run, js, &out)) return out;
  journal.sync();

  const double t_out = now_s();
  write_map_outputs(st, options, cells, &out);
  out.output_time = now_s() - t_out;
  out.wall_time = now_s() - t0;
  return out;
}

}  // namespace pronk::optimize::map
