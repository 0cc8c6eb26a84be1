#include "optimize/journal.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/crash_point.hpp"
#include "optimize/progress.hpp"
#include "optimize/scenario.hpp"
#include "optimize/study.hpp"

namespace pronk::optimize {

using nlohmann::json;

std::string record_checksum(const json& record, const std::string& previous) {
  if (!record.is_object() || !record.contains("checksum"))
    return fnv1a_hex(previous + record.dump());
  json content = record;
  content.erase("checksum");
  return fnv1a_hex(previous + content.dump());
}

json sealed(json record, const std::string& previous) {
  record.erase("checksum");
  record["checksum"] = record_checksum(record, previous);
  return record;
}

// ---- reading ---------------------------------------------------------------------------

JournalReader::JournalReader(std::istream& in, std::string path)
    : in_(in), path_(std::move(path)) {}

void JournalReader::check_header(const json& header) {
  const auto it = header.find("format");
  if (it == header.end()) {
    format_ = 1;  // an older pronk's journal: every line sealed on its own
    return;
  }
  if (!it->is_number_integer() || (*it != 1 && *it != kJournalFormat)) {
    throw io::InputError(path_, "line 1 /format",
                         "journal format 1 or " + std::to_string(kJournalFormat) +
                             " (a newer pronk wrote this journal?)",
                         io::describe(*it));
  }
  format_ = it->get<int>();
}

bool JournalReader::next(json* record) {
  std::string text;
  if (!std::getline(in_, text)) return false;
  if (in_.eof()) {  // no newline after it: a torn write, necessarily the last line
    torn_ = true;
    return false;
  }
  ++line_;
  const std::string where = "line " + std::to_string(line_);
  json j;
  try {
    j = io::parse_json_text(text, path_);
  } catch (const io::InputError& e) {
    throw io::InputError(path_, where, "a JSON record", e.found());
  }
  if (!j.is_object()) throw io::InputError(path_, where, "a JSON object record", io::describe(j));
  if (line_ == 1) check_header(j);
  const auto it = j.find("checksum");
  if (it == j.end()) {
    throw io::InputError(path_, where + " /checksum",
                         "a record with its checksum (journals of this pronk carry one; delete "
                         "the journal to start over)",
                         "no checksum");
  }
  const bool chained = format_ >= 2 && line_ > 1;
  const std::string expected = record_checksum(j, chained ? previous_ : "");
  if (!it->is_string() || it->get<std::string>() != expected) {
    throw io::InputError(
        path_, where + " /checksum",
        "checksum " + expected +
            (chained ? " of the record and the line before it (the record was edited, or a line "
                       "before it was deleted, duplicated, moved or inserted; delete the journal "
                       "to start over)"
                     : " of the record's content (the journal was edited or corrupted; delete it "
                       "to start over)"),
        io::describe(*it));
  }
  previous_ = expected;
  good_bytes_ += text.size() + 1;
  *record = std::move(j);
  return true;
}

namespace {

// A format-1 journal rewritten in format 2 (the same records, chained). Returns the last
// checksum. Old journals are small (this pronk writes format 2), so the text is built whole.
std::string migrate_to_chained(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  JournalReader reader(in, path);
  std::string text, previous;
  for (json j; reader.next(&j);) {
    if (reader.line_number() == 1) j["format"] = kJournalFormat;
    j = sealed(std::move(j), previous);
    previous = j.at("checksum").get<std::string>();
    text += j.dump() + "\n";
  }
  io::write_file_atomic(path, text);
  return previous;
}

// One evaluation record from its parsed line (nlohmann exceptions for missing fields).
JournalRecord evaluation_record(const json& j, long line_number) {
  JournalRecord r;
  r.index = j.at("index").get<long>();
  r.purpose = j.at("purpose").get<std::string>();
  r.x = j.at("x").get<std::vector<double>>();
  r.result.ok = j.at("ok").get<bool>();
  r.result.cost = j.at("cost").get<double>();
  r.result.constraints = j.at("constraints").get<std::vector<double>>();
  r.result.failure = j.value("failure", "");
  if (j.contains("objectives")) r.objectives = j.at("objectives").get<std::vector<double>>();
  r.line = j;
  r.line_number = line_number;
  return r;
}

// Reads a study journal through `reader`: the header into *header, each record to on_record.
void read_study_journal(JournalReader& reader, json* header,
                        const std::function<void(JournalRecord&&)>& on_record) {
  long expected_index = 0;
  for (json j; reader.next(&j);) {
    const long lineno = reader.line_number();
    const std::string where = "line " + std::to_string(lineno);
    if (lineno == 1) {
      if (!io::holds(j, "type", "header"))
        throw io::InputError(reader.path(), where, "a journal header record", io::describe(j));
      *header = std::move(j);
      continue;
    }
    JournalRecord r;
    try {
      r = evaluation_record(j, lineno);
    } catch (const json::exception& e) {
      throw io::InputError(reader.path(), where, "an evaluation record", e.what());
    }
    if (r.index != expected_index) {
      throw io::InputError(reader.path(), where + " /index",
                           "index " + std::to_string(expected_index) +
                               " (record k is on line k + 2: a line was deleted, duplicated, "
                               "moved or inserted)",
                           std::to_string(r.index));
    }
    ++expected_index;
    on_record(std::move(r));
  }
}

JournalContents read_contents(JournalReader& reader) {
  JournalContents c;
  read_study_journal(reader, &c.header,
                     [&](JournalRecord&& r) { c.records.push_back(std::move(r)); });
  c.end = reader.end();
  c.torn_tail = c.end.torn_tail;
  return c;
}

}  // namespace

JournalEnd JournalReader::end() const {
  return JournalEnd{format_, line_, torn_, good_bytes_, previous_};
}

std::string prepare_for_append(const std::string& path, const JournalEnd& end) {
  std::error_code ec;
  if (end.torn_tail && end.good_bytes < std::filesystem::file_size(path, ec))
    std::filesystem::resize_file(path, end.good_bytes);
  if (end.format < kJournalFormat && end.lines > 0) return migrate_to_chained(path);
  return end.last_checksum;
}

JournalContents parse_journal(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  JournalReader reader(in, path);
  return read_contents(reader);
}

JournalContents read_journal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  JournalReader reader(in, path);
  return read_contents(reader);
}

void for_each_journal_record(const std::string& path,
                             const std::function<void(const JournalRecord&)>& on_record) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;
  JournalReader reader(in, path);
  json header;
  read_study_journal(reader, &header, [&](JournalRecord&& r) { on_record(r); });
}

// ---- writing ---------------------------------------------------------------------------

JournalWriter::JournalWriter(const std::string& path, const json& header, std::string previous,
                             double sync_interval)
    : path_(path), previous_(std::move(previous)), sync_interval_(sync_interval) {
  const bool fresh = previous_.empty();
  file_ = std::fopen(path.c_str(), fresh ? "w" : "a");
  if (!file_) throw std::runtime_error("cannot open journal " + path + ": " + std::strerror(errno));
  if (fresh) {
    json h = header;
    h["format"] = kJournalFormat;
    append(h);
    sync();
  }
}

JournalWriter::~JournalWriter() {
  if (!file_) return;
  ::fsync(fileno(file_));
  std::fclose(file_);
}

void JournalWriter::append(const json& record) {
  json line = sealed(record, previous_);
  const std::string text = line.dump() + "\n";
  if (io::crash_point_is_next()) {  // a kill in the middle of the write (tests only)
    std::fwrite(text.data(), 1, text.size() / 2, file_);
    std::fflush(file_);
  }
  io::crash_point();
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
    throw std::runtime_error("cannot write journal " + path_ + ": " + std::strerror(errno));
  previous_ = line.at("checksum").get<std::string>();
  if (sync_interval_ <= 0.0 || monotonic_seconds() - last_sync_ > sync_interval_) sync();
}

void JournalWriter::sync() {
  if (::fsync(fileno(file_)) != 0)
    throw std::runtime_error("cannot sync journal " + path_ + ": " + std::strerror(errno));
  last_sync_ = monotonic_seconds();
}

json journal_record(long index, const char* purpose, const Evaluation& e,
                    const std::vector<std::string>& names) {
  json values = json::object();
  for (size_t i = 0; i < names.size() && i < e.values.size(); ++i) values[names[i]] = e.values[i];
  json metrics = json::object();
  for (const auto& [k, v] : e.aggregated) metrics[k] = v;
  json rec = {{"type", "evaluation"},
              {"index", index},
              {"purpose", purpose},
              {"x", e.unit},
              {"values", values},
              {"ok", e.ok},
              {"cost", e.cost},
              {"constraints", e.constraints},
              {"spectral_radius", e.spectral_radius},
              {"metrics", metrics},
              {"simulations", e.simulations},
              {"strides", e.strides}};
  if (!e.ok) rec["failure"] = e.failure;
  if (!e.objectives.empty()) rec["objectives"] = e.objectives;
  return rec;
}

std::vector<long> verification_sample(long count, long sample, std::uint64_t seed) {
  std::vector<long> all(static_cast<size_t>(std::max(count, 0L)));
  std::iota(all.begin(), all.end(), 0L);
  if (sample <= 0 || sample >= count) return all;
  // The first `sample` places of a Fisher-Yates shuffle.
  SplitMix64 rng(seed);
  for (long i = 0; i < sample; ++i) {
    const long j = i + static_cast<long>(rng.next() % static_cast<std::uint64_t>(count - i));
    std::swap(all[static_cast<size_t>(i)], all[static_cast<size_t>(j)]);
  }
  all.resize(static_cast<size_t>(sample));
  std::sort(all.begin(), all.end());
  return all;
}

}  // namespace pronk::optimize
