#include "optimize/journal_check.hpp"

#include "io/load/input_error.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace {

// The first key at which two records differ ("" when equal).
std::string first_difference(const json& a, const json& b) {
  for (auto it = a.begin(); it != a.end(); ++it) {
    if (!b.contains(it.key()) || b.at(it.key()).dump() != it.value().dump()) return it.key();
  }
  for (auto it = b.begin(); it != b.end(); ++it) {
    if (!a.contains(it.key())) return it.key();
  }
  return "";
}

// Throws unless `record` is what its re-evaluation `e` gives.
void compare(const JournalRecord& record, const Evaluation& e, const Evaluator& ev,
             const std::string& path) {
  const json again = journal_record(record.index, record.purpose.c_str(), e, ev.variable_names());
  json recorded = record.line;
  recorded.erase("checksum");
  const std::string key = first_difference(recorded, again);
  if (key.empty()) return;
  auto text = [&](const json& j) {
    const std::string d = j.contains(key) ? j.at(key).dump() : "nothing";
    return d.size() > 80 ? d.substr(0, 77) + "..." : d;
  };
  throw io::InputError(path, "line " + std::to_string(record.line_number) + " /" + key,
                       "the value its re-evaluation gives, " + text(again) +
                           " (evaluations are deterministic; a journal edited or written by "
                           "another build cannot be resumed)",
                       text(recorded));
}

}  // namespace

void check_last_record(const JournalContents& journal, const Evaluator& ev,
                       const std::string& path) {
  if (journal.records.empty()) return;
  const JournalRecord& last = journal.records.back();
  compare(last, ev.evaluate_full(last.x), ev, path);
}

long verify_records(const JournalContents& journal, const Evaluator& ev, long sample,
                    std::uint64_t seed, const std::string& path) {
  const std::vector<long> picked =
      verification_sample(static_cast<long>(journal.records.size()), sample, seed);
  constexpr size_t kBatch = 64;  // points evaluated at once (bounded memory)
  for (size_t begin = 0; begin < picked.size(); begin += kBatch) {
    const size_t end = std::min(picked.size(), begin + kBatch);
    std::vector<std::vector<double>> xs;
    for (size_t i = begin; i < end; ++i)
      xs.push_back(journal.records[static_cast<size_t>(picked[i])].x);
    const std::vector<Evaluation> again = ev.evaluate_full_batch(xs);
    for (size_t i = begin; i < end; ++i)
      compare(journal.records[static_cast<size_t>(picked[i])], again[i - begin], ev, path);
  }
  return static_cast<long>(picked.size());
}

}  // namespace pronk::optimize
