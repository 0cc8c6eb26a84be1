// The study journal: an append-only JSON-lines file, one record per
// evaluation, flushed and fsynced per record; a torn last line is skipped on
// reading. It holds no timings (they go to timings.csv), so a study gives the
// same journal bytes whatever the thread count.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/evaluator.hpp"

namespace pronk::optimize {

struct JournalRecord {
  long index = 0;
  std::string purpose;    ///< "objective" or "gradient"
  std::vector<double> x;  ///< optimizer coordinates
  ProblemEvaluation result;
  nlohmann::json line;  ///< the whole record as read
};

struct JournalContents {
  nlohmann::json header;  ///< first line (study name, hash, parameters)
  std::vector<JournalRecord> records;
  bool torn_tail = false;  ///< the last line was incomplete and skipped
};

/// Reads a journal; InputError if the file exists but its header is unreadable.
JournalContents read_journal(const std::string& path);

class JournalWriter {
 public:
  /// Opens `path` for appending; writes `header` first if the file is new/empty.
  JournalWriter(const std::string& path, const nlohmann::json& header);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  /// Appends one line and fsyncs it.
  void append(const nlohmann::json& record);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
};

/// One journal line for an evaluation.
nlohmann::json journal_record(long index, const char* purpose, const Evaluation& e,
                              const std::vector<std::string>& names);

}  // namespace pronk::optimize
