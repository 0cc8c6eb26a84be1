#include "optimize/study_history.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "io/write/atomic_file.hpp"
#include "io/write/table.hpp"
#include "optimize/parameters.hpp"

namespace pronk::optimize {

namespace {

constexpr const char* kTimingsHeader = "index,wall_time_s,binding_time_s,simulations,strides\n";

std::string csv_num(double x) { return io::exact_number(x); }

// The CSV line of one journal record; `best` is the best feasible cost so far (updated).
std::string history_line(const JournalRecord& r, const Evaluator& ev, double* best) {
  const bool feasible =
      r.result.ok && std::all_of(r.result.constraints.begin(), r.result.constraints.end(),
                                 [](double g) { return g <= 1e-8; });
  if (feasible) *best = std::min(*best, r.result.cost);
  std::string out = std::to_string(r.index) + "," + r.purpose + "," + (r.result.ok ? "1" : "0") +
                    "," + csv_num(r.result.cost) + "," + (feasible ? "1" : "0") + "," +
                    (std::isfinite(*best) ? csv_num(*best) : std::string(""));
  const auto values = physical_values(ev.config().parameters, r.x);
  // Appended piecewise: `"," + std::string` trips GCC 12's false -Wrestrict (bug 105651).
  for (double v : values) out.append(",").append(csv_num(v));
  for (double g : r.result.constraints) out.append(",").append(csv_num(g));
  out.append(",").append(csv_num(r.line.value("spectral_radius", 0.0))).append("\n");
  return out;
}

// timings.csv rebuilt for a resumed journal: the existing line of each record (the last
// one written for its index), or one with empty times.
std::string rebuilt_timings(const std::string& path, const JournalContents& journal) {
  std::map<long, std::string> lines;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    if (in.eof()) break;  // torn
    char* end = nullptr;
    const long index = std::strtol(line.c_str(), &end, 10);
    if (end != line.c_str() && *end == ',') lines[index] = line;
  }
  std::string out = kTimingsHeader;
  for (const JournalRecord& r : journal.records) {
    const auto it = lines.find(r.index);
    if (it != lines.end()) {
      out += it->second + "\n";
    } else {
      out += std::to_string(r.index) + ",,," + std::to_string(r.line.value("simulations", 0L)) +
             "," + std::to_string(r.line.value("strides", 0L)) + "\n";
    }
  }
  return out;
}

}  // namespace

void write_history(const std::string& dir, const std::string& journal_path, const Evaluator& ev) {
  std::string out = "index,purpose,ok,cost,feasible,best_feasible_cost";
  for (const auto& n : ev.variable_names()) out += "," + n;
  for (size_t c = 0; c < ev.config().constraints.size(); ++c) out += ",g" + std::to_string(c);
  out += ",spectral_radius\n";
  double best = INFINITY;
  for_each_journal_record(journal_path,
                          [&](const JournalRecord& r) { out += history_line(r, ev, &best); });
  io::write_file_atomic(dir + "/history.csv", out);
}

TimingsFile::TimingsFile(const std::string& dir, const JournalContents* resumed) {
  const std::string path = dir + "/timings.csv";
  io::write_file_atomic(path, resumed ? rebuilt_timings(path, *resumed) : kTimingsHeader);
  file_ = std::fopen(path.c_str(), "a");
}

TimingsFile::~TimingsFile() {
  if (file_) std::fclose(file_);
}

void TimingsFile::write(long index, const Evaluation& e) {
  if (!file_) return;
  std::fprintf(file_, "%ld,%.6f,%.6f,%ld,%ld\n", index, e.wall_time, e.binding_time, e.simulations,
               e.strides);
  std::fflush(file_);
}

}  // namespace pronk::optimize
