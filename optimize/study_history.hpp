// The two per-evaluation tables of a study next to its journal: history.csv (costs,
// feasibility, parameter values, constraints; written at the end, streamed from the
// journal so memory does not grow with the number of evaluations) and timings.csv (wall
// and binding times, which the journal leaves out so that it does not depend on the
// machine; written as the study runs, one line per journal record).
#pragma once

#include <cstdio>
#include <string>

#include "optimize/evaluator.hpp"
#include "optimize/journal.hpp"

namespace pronk::optimize {

/// Writes DIR/history.csv (atomically) from the study journal at `journal_path`, read one
/// record at a time.
void write_history(const std::string& dir, const std::string& journal_path, const Evaluator& ev);

/// DIR/timings.csv while a study runs. Each evaluation's line is written (and flushed)
/// before its journal record, so a kill between the two leaves a line too many, never one
/// too few; on resume the file is rebuilt to exactly one line per journal record first (a
/// line without a record dropped; a record without a line, from a file lost or written by
/// an older pronk, gets one with its times empty).
class TimingsFile {
 public:
  /// A new file, or with `resumed` (the journal being resumed) the rebuilt one.
  TimingsFile(const std::string& dir, const JournalContents* resumed);
  ~TimingsFile();
  TimingsFile(const TimingsFile&) = delete;
  TimingsFile& operator=(const TimingsFile&) = delete;
  /// Appends the line of evaluation `index`. I/O errors are ignored (timings are advisory).
  void write(long index, const Evaluation& e);

 private:
  std::FILE* file_ = nullptr;
};

}  // namespace pronk::optimize
