#include "optimize/journal.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "optimize/study.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"

namespace pronk::optimize {

using nlohmann::json;

std::string record_checksum(const json& record) {
  if (!record.is_object() || !record.contains("checksum")) return fnv1a_hex(record.dump());
  json content = record;
  content.erase("checksum");
  return fnv1a_hex(content.dump());
}

json sealed(json record) {
  record.erase("checksum");
  record["checksum"] = record_checksum(record);
  return record;
}

void check_seal(const json& record, const std::string& path, long line_number) {
  const std::string where = "line " + std::to_string(line_number) + " /checksum";
  if (!record.is_object()) {
    throw io::InputError(path, "line " + std::to_string(line_number), "a JSON object record",
                         io::describe(record));
  }
  const auto it = record.find("checksum");
  if (it == record.end()) {
    throw io::InputError(path, where,
                         "a record with its checksum (journals of this pronk carry one; delete "
                         "the journal to start over)",
                         "no checksum");
  }
  const std::string expected = record_checksum(record);
  if (!it->is_string() || it->get<std::string>() != expected) {
    throw io::InputError(path, where,
                         "checksum " + expected +
                             " of the record's content (the journal was edited or corrupted; "
                             "delete it to start over)",
                         io::describe(*it));
  }
}

namespace {

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
  r.line = j;
  r.line_number = line_number;
  return r;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t nl = text.find('\n', begin);
    const std::size_t end = nl == std::string::npos ? text.size() : nl;
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

}  // namespace

JournalContents parse_journal(const std::string& text, const std::string& path) {
  JournalContents c;
  const std::vector<std::string> lines = split_lines(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    const long lineno = static_cast<long>(i) + 1;
    const std::string where = "line " + std::to_string(lineno);
    if (i + 1 == lines.size() && text.back() != '\n') {
      c.torn_tail = true;  // a last line without its newline is a torn write
      break;
    }
    json j;
    try {
      j = io::parse_json_text(lines[i], path);
    } catch (const io::InputError& e) {
      throw io::InputError(path, where, "a JSON record", e.found());
    }
    check_seal(j, path, lineno);
    if (i == 0) {
      if (j.value("type", "") != "header") {
        throw io::InputError(path, where, "a journal header record", io::describe(j));
      }
      c.header = j;
      continue;
    }
    try {
      c.records.push_back(evaluation_record(j, lineno));
    } catch (const json::exception& e) {
      throw io::InputError(path, where, "an evaluation record", e.what());
    }
  }
  return c;
}

JournalContents read_journal(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_journal(buf.str(), path);
}

JournalWriter::JournalWriter(const std::string& path, const json& header) : path_(path) {
  bool empty = true;
  {
    std::ifstream in(path);
    empty = !in || in.peek() == std::ifstream::traits_type::eof();
  }
  file_ = std::fopen(path.c_str(), "a");
  if (!file_) throw std::runtime_error("cannot open journal " + path + ": " + std::strerror(errno));
  if (empty) append(header);
}

JournalWriter::~JournalWriter() {
  if (file_) std::fclose(file_);
}

void JournalWriter::append(const json& record) {
  const std::string text = sealed(record).dump() + "\n";
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0 ||
      ::fsync(fileno(file_)) != 0) {
    throw std::runtime_error("cannot write journal " + path_ + ": " + std::strerror(errno));
  }
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
  return rec;
}

}  // namespace pronk::optimize
