#include "optimize/journal.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "sim/io/input_error.hpp"
#include "sim/io/json_reader.hpp"

namespace pronk::optimize {

using nlohmann::json;

JournalContents read_journal(const std::string& path) {
  JournalContents c;
  std::ifstream in(path);
  if (!in) return c;
  std::string line;
  long lineno = 0;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  // A line without its newline at the very end is a torn write.
  in.clear();
  for (size_t i = 0; i < lines.size(); ++i) {
    ++lineno;
    json j;
    try {
      j = json::parse(lines[i]);
    } catch (const json::exception&) {
      if (i + 1 == lines.size()) {
        c.torn_tail = true;
        break;
      }
      throw io::InputError(path, "line " + std::to_string(lineno), "a JSON record",
                           "an unreadable line in the middle of the journal");
    }
    if (i == 0) {
      if (!j.is_object() || j.value("type", "") != "header") {
        throw io::InputError(path, "line 1", "a journal header record", io::describe(j));
      }
      c.header = j;
      continue;
    }
    JournalRecord r;
    try {
      r.index = j.at("index").get<long>();
      r.purpose = j.at("purpose").get<std::string>();
      r.x = j.at("x").get<std::vector<double>>();
      r.result.ok = j.at("ok").get<bool>();
      r.result.cost = j.at("cost").get<double>();
      r.result.constraints = j.at("constraints").get<std::vector<double>>();
      r.result.failure = j.value("failure", "");
    } catch (const json::exception& e) {
      if (i + 1 == lines.size()) {
        c.torn_tail = true;
        break;
      }
      throw io::InputError(path, "line " + std::to_string(lineno), "an evaluation record",
                           e.what());
    }
    r.line = j;
    c.records.push_back(std::move(r));
  }
  return c;
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
  const std::string text = record.dump() + "\n";
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
