// The study journal: an append-only JSON-lines file, one record per
// evaluation, flushed and fsynced per record; a torn last line is skipped on
// reading. Every line carries a checksum of its content, checked on reading. It holds no timings
// (they go to timings.csv), so a study gives the same journal bytes whatever the thread count.
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
  nlohmann::json line;   ///< the whole record as read
  long line_number = 0;  ///< 1-based line of the journal file
};

struct JournalContents {
  nlohmann::json header;  ///< first line (study name, hash, parameters)
  std::vector<JournalRecord> records;
  bool torn_tail = false;  ///< the last line was incomplete and skipped
};

/// Reads a journal; an empty result when the file does not exist. InputError (naming the
/// line) for an unreadable header, a line in the middle that is not a record, or a line
/// whose checksum does not match its content (edited, corrupted, or written by a pronk
/// without checksums).
JournalContents read_journal(const std::string& path);
/// The same from the journal's text; `path` names it in errors.
JournalContents parse_journal(const std::string& text, const std::string& path);

/// FNV-1a 64 (16 hex digits) of a record's canonical text (dump() without its "checksum").
std::string record_checksum(const nlohmann::json& record);
/// The record with its "checksum" added: what every journal line holds.
nlohmann::json sealed(nlohmann::json record);
/// Throws io::InputError at `path` line `line_number` unless `record` (a JSON object) carries
/// the checksum of its content.
void check_seal(const nlohmann::json& record, const std::string& path, long line_number);

class JournalWriter {
 public:
  /// Opens `path` for appending; writes `header` first if the file is new/empty.
  JournalWriter(const std::string& path, const nlohmann::json& header);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  /// Appends one line (the record sealed with its checksum) and fsyncs it.
  void append(const nlohmann::json& record);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
};

/// One journal line for an evaluation.
nlohmann::json journal_record(long index, const char* purpose, const Evaluation& e,
                              const std::vector<std::string>& names);

}  // namespace pronk::optimize
