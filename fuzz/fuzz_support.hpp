// Shared by the libFuzzer targets: the input as a JSON document, read the way
// every loader reads a file (parse_json_text), and a loader run the way the CLI runs
// it. An io::InputError is the one expected failure (bad input, exit 2); any other
// exception escapes the target and libFuzzer reports it as a crash, since the CLI
// would end with exit 1 and a raw message (e.g. nlohmann's "unresolved reference token")
// on the same input: a bug, as is a sanitizer report.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"

namespace pronk::fuzz {

/// The input as text.
inline std::string text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Runs `load` on fuzz input: returns on success or an InputError; anything else escapes.
template <class Load>
void expect_only_input_errors(Load&& load) {
  try {
    load();
  } catch (const io::InputError&) {
  }
}

/// The input parsed as a JSON document; nothing when it is not one (an InputError).
inline std::optional<nlohmann::json> document(const std::string& input) {
  try {
    return io::parse_json_text(input, "fuzz.json");
  } catch (const io::InputError&) {
    return std::nullopt;
  }
}

}  // namespace pronk::fuzz
