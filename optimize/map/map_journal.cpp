#include "optimize/map/map_journal.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <utility>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/write/table.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::optimize::map {

using nlohmann::json;

namespace {

std::string num(double x) { return io::exact_number(x); }

// Refuses line `line` of the journal (`at`: " /key" or "").
[[noreturn]] void refuse(const std::string& path, long line, const std::string& at,
                         const std::string& expected, const std::string& found) {
  throw io::InputError(path, "line " + std::to_string(line) + at, expected, found);
}

// Why a trial cannot be what run_trial gives ("" when it can).
std::string trial_problem(const MapStudy& st, const TrialOutcome& t) {
  if (t.status != "completed" && t.status != "fell" && t.status != "diverged")
    return "status \"" + t.status + "\"";
  const bool settled = t.settle_strides >= 0;
  const std::string strides = "settled from stride " + std::to_string(t.settle_strides) + " of " +
                              std::to_string(t.strides) + " (" + t.status + ")";
  if (t.strides < 0 || t.settle_strides < -1 ||
      (settled && (t.settle_strides >= t.strides || t.status != "completed")))
    return strides;
  const bool stabilized = settled && t.settle_strides <= st.stabilized.within_strides &&
                          t.strides - t.settle_strides >= st.stabilized.hold_strides;
  if (t.stabilized != stabilized)
    return std::string(t.stabilized ? "stabilized" : "not stabilized") + " when " + strides;
  if (!std::isfinite(t.duty_mean) || !std::isfinite(t.peak_force)) return "a non-finite number";
  return "";
}

void check_cell(const MapStudy& st, const CellResult& c, const MapJournalState& js,
                const std::string& path, long line) {
  if (!js.boundaries.empty()) {
    refuse(path, line, " /task",
           "no cell after a boundary record (rows are bisected once every cell is done)",
           "a cell record");
  }
  if (c.index < 0 || c.index >= st.cells()) {
    refuse(path, line, " /cell", "a cell of the grid, 0 to " + std::to_string(st.cells() - 1),
           std::to_string(c.index));
  }
  if (const auto it = js.cell_lines.find(c.index); it != js.cell_lines.end()) {
    refuse(path, line, " /cell", "each cell recorded once",
           "cell " + std::to_string(c.index) + " again (first on line " +
               std::to_string(it->second) + ")");
  }
  if (c.trials.size() != st.models.size()) {
    refuse(path, line, " /trials",
           std::to_string(st.models.size()) + " lists of trials, one per model",
           std::to_string(c.trials.size()));
  }
  for (size_t m = 0; m < c.trials.size(); ++m) {
    const std::string at = " /trials/" + std::to_string(m);
    if (static_cast<long>(c.trials[m].size()) != st.trials.count) {
      refuse(path, line, at,
             run::count_text(st.trials.count, "trial") + " (the study's trial count)",
             std::to_string(c.trials[m].size()));
    }
    for (size_t t = 0; t < c.trials[m].size(); ++t) {
      const std::string problem = trial_problem(st, c.trials[m][t]);
      if (!problem.empty()) {
        refuse(path, line, at + "/" + std::to_string(t),
               "a trial as the simulator and the study's \"stabilized\" rule give it", problem);
      }
    }
  }
  const bool owner = st.stability && stability_owner(st, c.index) == c.index;
  if (c.has_stability != owner || (owner && !(c.spectral_radius >= 0.0))) {
    refuse(path, line, " /spectral_radius",
           owner ? "a spectral radius >= 0 (the cell owns its scene's stride map)"
                 : "no spectral radius (another cell, or none, owns its scene's stride map)",
           c.has_stability ? num(c.spectral_radius) : "none");
  }
}

// The summaries of the journal's cells (every cell of the grid is there).
std::vector<CellSummary> journal_summaries(const MapStudy& st, const MapJournalState& js) {
  std::vector<CellResult> cells;
  for (const auto& [index, c] : js.cells) cells.push_back(c);
  return summarize(st, cells);
}

// The bracket a row's bisection starts from, given its cells; throws unless it bisects.
BoundaryResult start_bracket(const MapStudy& st, const std::vector<CellSummary>& summaries,
                             long row, const std::string& path, long line) {
  const BoundaryResult b = initial_bracket(st, summaries, row);
  if (b.status != "bisected") {
    refuse(path, line, " /row",
           "a row whose cells bracket a boundary (row " + std::to_string(row) + "'s cells give \"" +
               b.status + "\": nothing to bisect)",
           "a bisected boundary");
  }
  return b;
}

void check_boundary(const MapStudy& st, const BoundaryResult& b, const MapJournalState& js,
                    const std::vector<CellSummary>& summaries, const std::string& path, long line) {
  if (static_cast<long>(js.cells.size()) != st.cells()) {
    refuse(path, line, " /task",
           "a boundary record only after every cell (" + std::to_string(st.cells()) + " cells)",
           "one after " + std::to_string(js.cells.size()) + " cells");
  }
  if (b.row < 0 || b.row >= st.rows()) {
    refuse(path, line, " /row", "a row of the grid, 0 to " + std::to_string(st.rows() - 1),
           std::to_string(b.row));
  }
  if (const auto it = js.boundary_lines.find(b.row); it != js.boundary_lines.end()) {
    refuse(path, line, " /row", "each row bisected once",
           "row " + std::to_string(b.row) + " again (first on line " + std::to_string(it->second) +
               ")");
  }
  // Walk the bisection the way the recorded bracket says it went: a probe at or below the
  // final good end found the row stabilized, one above it did not.
  BoundaryResult walk = start_bracket(st, summaries, b.row, path, line);
  const std::string start = "[" + num(walk.good) + ", " + num(walk.bad) + "]";
  double mid = 0.0;
  for (; walk.probes < b.probes && next_probe(st, walk, &mid); ++walk.probes)
    (b.good >= mid ? walk.good : walk.bad) = mid;
  const bool ended = !next_probe(st, walk, &mid);
  if (b.status != "bisected" || walk.probes != b.probes || !ended || walk.good != b.good ||
      walk.bad != b.bad || b.boundary != b.good) {
    refuse(path, line, " /good",
           "a bracket the bisection from the row's cells " + start +
               " reaches when it ends, the boundary its good end",
           "[" + num(b.good) + ", " + num(b.bad) + "] after " + std::to_string(b.probes) +
               " probes, boundary " + num(b.boundary) + " (" + b.status + ")");
  }
}

// The record as compute_task writes it: what a journal line holds without its checksum.
json canonical(const CellResult& c) {
  json j = to_json(c);
  j["task"] = "cell";
  return j;
}
json canonical(const BoundaryResult& b) {
  json j = to_json(b);
  j["task"] = "boundary";
  return j;
}

// Reads one record into js (checked); `summaries` are computed at the first boundary.
void read_record(const MapStudy& st, json j, long line, const std::string& path,
                 MapJournalState& js, std::vector<CellSummary>& summaries) {
  j.erase("checksum");
  const std::string task = j.value("task", "");
  json again;
  try {
    if (task == "cell") {
      CellResult c = cell_from_json(j);
      check_cell(st, c, js, path, line);
      again = canonical(c);
      js.cell_lines[c.index] = line;
      js.last_cell = c.index;
      js.cells[c.index] = std::move(c);
    } else if (task == "boundary") {
      const BoundaryResult b = boundary_from_json(j);
      if (summaries.empty() && static_cast<long>(js.cells.size()) == st.cells())
        summaries = journal_summaries(st, js);
      check_boundary(st, b, js, summaries, path, line);
      again = canonical(b);
      js.boundary_lines[b.row] = line;
      js.boundaries[b.row] = b;
    } else {
      refuse(path, line, " /task", "\"cell\" or \"boundary\"",
             io::describe(j.value("task", json())));
    }
  } catch (const json::exception& e) {
    refuse(path, line, "", "a map journal record", e.what());
  }
  if (again.dump() != j.dump())
    refuse(path, line, "", "a record of exactly the keys and types pronk writes", j.dump());
}

}  // namespace

json map_journal_header(const MapStudy& st) {
  return json{{"type", "pronk_map_journal"}, {"name", st.name}, {"hash", st.hash}};
}

MapJournalState read_map_journal(const std::string& path, const MapStudy& st) {
  MapJournalState js;
  std::ifstream in(path, std::ios::binary);
  if (!in) return js;
  JournalReader reader(in, path);
  std::vector<CellSummary> summaries;
  for (json j; reader.next(&j);) {
    if (reader.line_number() > 1) {
      read_record(st, std::move(j), reader.line_number(), path, js, summaries);
    } else if (!io::holds(j, "type", "pronk_map_journal") || !io::holds(j, "hash", st.hash)) {
      throw io::InputError(path, "/hash", "the journal of this map study (hash " + st.hash + ")",
                           j.contains("hash") ? io::describe(j.at("hash")) : "no hash");
    } else {
      js.exists = true;
    }
  }
  js.end = reader.end();
  return js;
}

long verify_map_journal(const MapJournalState& js, const MapStudy& st, TaskRunner& runner,
                        long sample, std::uint64_t seed, const std::string& path) {
  // Every record by line: its task and what computing it again must give.
  std::map<long, std::pair<MapTask, json>> records;
  for (const auto& [index, line] : js.cell_lines)
    records[line] = {MapTask{0, index, 0.0, 0.0}, canonical(js.cells.at(index))};
  if (!js.boundaries.empty()) {
    const std::vector<CellSummary> summaries = journal_summaries(st, js);
    for (const auto& [row, line] : js.boundary_lines) {
      const BoundaryResult b = start_bracket(st, summaries, row, path, line);
      records[line] = {MapTask{1, row, b.good, b.bad}, canonical(js.boundaries.at(row))};
    }
  }
  std::vector<long> lines;
  for (const auto& [line, r] : records) lines.push_back(line);
  std::set<long> picked;
  if (sample >= 0)
    for (long i : verification_sample(static_cast<long>(lines.size()), sample, seed))
      picked.insert(lines[static_cast<size_t>(i)]);
  const long verified = static_cast<long>(picked.size());
  if (js.last_cell >= 0) picked.insert(js.cell_lines.at(js.last_cell));
  std::vector<MapTask> tasks;
  std::map<std::pair<int, long>, long> line_of;
  for (long line : picked) {
    const MapTask& t = records.at(line).first;
    tasks.push_back(t);
    line_of[{t.kind, t.index}] = line;
  }
  std::set<long> differ;
  runner.run(
      st, tasks,
      [&](const MapTask& t, const json& r) {
        const long line = line_of.at({t.kind, t.index});
        if (r.dump() != records.at(line).second.dump()) differ.insert(line);
      },
      nullptr);
  if (!differ.empty()) {
    const MapTask& t = records.at(*differ.begin()).first;
    refuse(path, *differ.begin(), "",
           "the record its re-computation gives (cells and bisections are deterministic; a "
           "journal edited or written by another build cannot be resumed)",
           std::string("a different record for ") + (t.kind == 0 ? "cell " : "row ") +
               std::to_string(t.index));
  }
  return verified;
}

}  // namespace pronk::optimize::map
