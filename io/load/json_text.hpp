// JSON text to a document, strictly, for every input pronk reads (scenes, mechanism
// scenes, studies, map studies, designs, journal lines, --set values): nesting bounded
// before parsing, no NUL byte (nlohmann's parser stops at one, which would hide whatever
// follows it), no key given twice in one object (which one should win is ambiguous),
// nothing after the value. Every refusal is an InputError.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/load/input_error.hpp"

namespace pronk::io {

/// Deepest nesting of arrays and objects a JSON input may have.
inline constexpr std::size_t kMaxJsonDepth = 128;

/// Nesting depth of JSON text ('[' and '{' outside strings), found without parsing.
std::size_t json_nesting_depth(std::string_view text);

/// Parses JSON text read from `file` (named in errors). InputError for nesting deeper
/// than kMaxJsonDepth (checked before parsing: deep nesting would overflow the stack),
/// a NUL byte, a syntax error (trailing bytes included), a key given twice in one object
/// (the error's pointer names the second one) or a number beyond the double range.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

/// Parses a value given on the command line (a --set value) as strictly as
/// parse_json_text; nothing when `text` is not JSON syntax at all (a bare word). Errors
/// name `origin` as the file and `base_pointer` (where the value goes) as the pointer.
std::optional<nlohmann::json> parse_json_value(const std::string& text, const std::string& origin,
                                               const std::string& base_pointer);

}  // namespace pronk::io
