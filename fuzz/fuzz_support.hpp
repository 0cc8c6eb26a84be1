// Shared by the libFuzzer targets: the input as a JSON document, read the way
// every loader reads a file (nesting bounded before parsing). Any outcome but a
// crash, a sanitizer report or an exception other than InputError is fine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sim/io/input_error.hpp"
#include "sim/io/json_reader.hpp"

namespace pronk::fuzz {

/// The input as text.
inline std::string text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
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
