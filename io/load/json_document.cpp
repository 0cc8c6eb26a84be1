// A JSON document from a file, and the command line's --set overrides applied to it.
#include "io/load/json_document.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/json_text.hpp"

namespace pronk::io {

using json = nlohmann::json;

json read_json_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path, "", "a JSON file", "a directory");
  }
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "a readable JSON file", "no such file or unreadable");
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_json_text(buf.str(), path);
}

void apply_override(json& doc, const std::string& assignment) {
  const std::string where = "command line (--set " + assignment + ")";
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || assignment.empty() || assignment[0] != '/') {
    throw InputError("command line", "", "--set /json/pointer=value", "\"" + assignment + "\"");
  }
  const std::string ptr = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  const std::optional<json> parsed = parse_json_value(text, where, ptr);
  const json value = parsed ? *parsed : json(text);  // a bare word: a string
  json::json_pointer jp;
  try {
    jp = json::json_pointer(ptr);
  } catch (const json::exception& e) {
    throw InputError(where, ptr, "a valid JSON Pointer", e.what());
  }
  const std::string parent_ptr = jp.parent_pointer().to_string();
  json* parent = find_pointer(doc, parent_ptr);
  if (parent == nullptr) {
    throw InputError(where, ptr, "a pointer whose parent exists in the scene",
                     "no value at " + (parent_ptr.empty() ? "/" : parent_ptr));
  }
  const std::string last = jp.back();
  if (parent->is_array()) {
    std::size_t idx = 0;
    const bool numeric =
        !last.empty() && std::all_of(last.begin(), last.end(),
                                     [](unsigned char ch) { return std::isdigit(ch) != 0; });
    if (numeric) idx = std::stoul(last.size() > 9 ? std::string("999999999") : last);
    if (!numeric || idx >= parent->size()) {
      throw InputError(where, ptr, "an index below " + std::to_string(parent->size()),
                       "\"" + last + "\"");
    }
    (*parent)[idx] = value;
  } else if (parent->is_object()) {
    (*parent)[last] = value;
  } else {
    throw InputError(where, ptr, "an object or array at the parent", describe(*parent));
  }
}

}  // namespace pronk::io
