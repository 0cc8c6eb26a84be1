// The journals of studies and maps: append-only JSON-lines files, a header first and then
// one record per evaluation (a map: per cell or bisected row). A torn last line (a write
// cut short) is skipped on reading. They hold no timings (a study's go to timings.csv), so
// a run gives the same journal bytes whatever the thread count.
//
// Every line carries a "checksum" (FNV-1a 64, 16 hex digits). In format 2 (the header's
// "format": 2, what this pronk writes) it is chained: it covers the line's content and the
// checksum of the line before it, so a line deleted, duplicated, moved or inserted breaks
// the chain at the first line after the change, and a changed line breaks it at that line.
// Format 1 (older journals, no "format" in the header) checks each line on its own; it is
// read, and rewritten in format 2 before anything is appended.
//
// What the checksums cannot catch: anyone can recompute them (they are not a signature).
// A forger who edits a record and recomputes the chain from there passes every check on
// reading; only evaluating the record again does not (`--resume --verify`).
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <istream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/evaluator.hpp"

namespace pronk::optimize {

/// The journal format this pronk writes.
inline constexpr int kJournalFormat = 2;

/// FNV-1a 64 (16 hex digits) of `previous` followed by the record's canonical text (dump()
/// without its "checksum"). `previous` is the checksum of the line before in format 2, ""
/// for a header and for every line in format 1.
std::string record_checksum(const nlohmann::json& record, const std::string& previous = "");
/// The record with its "checksum" added, chained onto `previous`: what a journal line holds.
nlohmann::json sealed(nlohmann::json record, const std::string& previous = "");

/// Where a journal read to its end stands: what appending to it needs.
struct JournalEnd {
  int format = kJournalFormat;
  long lines = 0;                 ///< complete lines (the header included)
  bool torn_tail = false;         ///< a last line without its newline was skipped
  std::uintmax_t good_bytes = 0;  ///< bytes of the complete lines
  std::string last_checksum;      ///< what the next line chains onto
};

/// Reads any journal line by line (memory independent of its length), checking each
/// complete line: a JSON object whose checksum matches its content and, in format 2, the
/// line before. Errors are io::InputError naming the file, the line and the "/checksum".
class JournalReader {
 public:
  JournalReader(std::istream& in, std::string path);
  /// The next complete line (the header first); false at the end. A last line without its
  /// newline is a torn write: skipped (end().torn_tail).
  bool next(nlohmann::json* record);
  /// 1-based line of the record next() returned last.
  long line_number() const { return line_; }
  /// 2, or 1 for a header without "format" (set once the header was read).
  int format() const { return format_; }
  const std::string& path() const { return path_; }
  /// The reader's position, once next() returned false.
  JournalEnd end() const;

 private:
  void check_header(const nlohmann::json& header);
  std::istream& in_;
  std::string path_;
  long line_ = 0;
  int format_ = kJournalFormat;
  std::string previous_;
  bool torn_ = false;
  std::uintmax_t good_bytes_ = 0;
};

/// Makes the journal at `path`, read to its end (`end`, from JournalReader::end()), ready
/// for appending: cuts a torn last line, and rewrites a format-1 journal in format 2.
/// Returns the checksum the next line chains onto.
std::string prepare_for_append(const std::string& path, const JournalEnd& end);

struct JournalRecord {
  long index = 0;
  std::string purpose;    ///< "objective" or "gradient"
  std::vector<double> x;  ///< optimizer coordinates
  ProblemEvaluation result;
  /// A multi-objective study's objective values ("objectives"); empty otherwise.
  std::vector<double> objectives;
  nlohmann::json line;   ///< the whole record as read
  long line_number = 0;  ///< 1-based line of the journal file
};

struct JournalContents {
  nlohmann::json header;  ///< first line (study name, hash, parameters)
  std::vector<JournalRecord> records;
  bool torn_tail = false;  ///< the last line was incomplete and skipped
  JournalEnd end;          ///< for prepare_for_append
};

/// Reads a study journal; an empty result when the file does not exist. io::InputError
/// (naming the line) for an unreadable header, a line in the middle that is not a record, a
/// checksum that does not match (see JournalReader), or an index out of sequence: record k
/// (line k + 2) must have index k.
JournalContents read_journal(const std::string& path);
/// The same from the journal's text; `path` names it in errors.
JournalContents parse_journal(const std::string& text, const std::string& path);
/// Streams the records of the study journal at `path` to `on_record` one at a time, checked
/// as read_journal checks them: memory independent of the journal's length.
void for_each_journal_record(const std::string& path,
                             const std::function<void(const JournalRecord&)>& on_record);

class JournalWriter {
 public:
  /// Appends to the journal at `path`, chaining onto `previous` (a JournalReader's
  /// last_checksum). With `previous` empty the file is created anew, `header` its first
  /// line (with "format" added). Each record is flushed to the OS at once (a killed process
  /// loses nothing) and fsynced when `sync_interval` [s] has passed since the last fsync
  /// (0: every record), and at the end.
  JournalWriter(const std::string& path, const nlohmann::json& header, std::string previous,
                double sync_interval = 0.0);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  /// Appends one line: the record sealed and chained.
  void append(const nlohmann::json& record);
  /// fsync now.
  void sync();

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  std::string previous_;
  double sync_interval_;
  double last_sync_ = 0.0;
};

/// One journal line for an evaluation (with "objectives" when the evaluation has them:
/// multi-objective studies only, so other journals keep their bytes).
nlohmann::json journal_record(long index, const char* purpose, const Evaluation& e,
                              const std::vector<std::string>& names);

/// Which of `count` records a verification re-evaluates: all of them (sample <= 0 or
/// sample >= count), or `sample` of them drawn without replacement by SplitMix64 from
/// `seed`. Ascending.
std::vector<long> verification_sample(long count, long sample, std::uint64_t seed);

}  // namespace pronk::optimize
