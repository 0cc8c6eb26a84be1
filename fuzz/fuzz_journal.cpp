// libFuzzer target over the study journal reader. Each input is read twice: as
// it is (the checksums reject almost every mutation) and with every line that is
// a JSON object sealed with its checksum first, chained onto the line before as
// format 2 requires, so the fuzzer also reaches the header's format, the index
// continuity check and the record parsing behind the checksum check.
#include <sstream>

#include "fuzz/fuzz_support.hpp"
#include "optimize/journal.hpp"

namespace {

std::string sealed_lines(const std::string& input) {
  std::istringstream in(input);
  std::string line, out, previous;
  bool first = true, chained = true;
  while (std::getline(in, line)) {
    const auto j = pronk::fuzz::document(line);
    if (j && j->is_object()) {
      if (first) chained = j->contains("format");  // format 1: each line on its own
      first = false;
      const nlohmann::json s = pronk::optimize::sealed(*j, chained ? previous : "");
      previous = s.at("checksum").get<std::string>();
      out += s.dump();
    } else {
      out += line;
    }
    if (!in.eof()) out += "\n";
  }
  return out;
}

void read(const std::string& text) {
  pronk::fuzz::expect_only_input_errors(
      [&] { (void)pronk::optimize::parse_journal(text, "fuzz.jsonl"); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input = pronk::fuzz::text(data, size);
  read(input);
  read(sealed_lines(input));
  return 0;
}
