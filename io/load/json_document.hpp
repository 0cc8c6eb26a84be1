// A JSON document from a file, and the command line's --set overrides applied to it.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace pronk::io {

/// Reads and parses a JSON file; InputError on a missing file, a directory, nesting deeper
/// than kMaxJsonDepth or a syntax error.
nlohmann::json read_json_file(const std::string& path);

/// Applies "--set /json/pointer=value" overrides to a document. The value is
/// parsed as JSON (a bare word that is not JSON is taken as a string). The
/// parent of the pointer must exist. InputError names the override.
void apply_override(nlohmann::json& doc, const std::string& assignment);

}  // namespace pronk::io
