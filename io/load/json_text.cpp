#include "io/load/json_text.hpp"

#include <algorithm>
#include <unordered_set>
#include <vector>

#include "io/load/json_reader.hpp"

namespace pronk::io {

using json = nlohmann::json;

std::size_t json_nesting_depth(std::string_view text) {
  std::size_t depth = 0, deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character cannot end the string
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

namespace {

// Follows the parser's events to know where it is (a JSON Pointer) and which keys each
// open object already has; a key seen twice in one object is an InputError naming it.
class DuplicateKeyCheck {
 public:
  DuplicateKeyCheck(std::string file, std::string base) : file_(std::move(file)), base_(base) {}

  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        begin_element();
        frames_.push_back({event == json::parse_event_t::object_start, {}, {}, 0});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        break;
      case json::parse_event_t::value:
        begin_element();
        break;
      case json::parse_event_t::key:
        add_key(parsed.get<std::string>());
        break;
    }
    return true;  // keep every value: the document is the plain parse's
  }

 private:
  struct Frame {
    bool object;
    std::unordered_set<std::string> keys;  // an object's keys so far
    std::string token;                     // the child being read: its key or index
    std::size_t next_index;                // an array's next element index
  };

  void begin_element() {
    if (!frames_.empty() && !frames_.back().object) {
      frames_.back().token = std::to_string(frames_.back().next_index++);
    }
  }

  void add_key(const std::string& key) {
    Frame& f = frames_.back();
    f.token = key;
    if (f.keys.insert(key).second) return;
    // Built with += only: GCC 12 warns falsely (-Wstringop-overflow) on "literal" + string&&.
    std::string pointer = base_;
    for (const Frame& open : frames_) {
      pointer += '/';
      pointer += pointer_escape(open.token);
    }
    std::string found = "\"";
    found += key;
    found += "\" a second time (which one holds is ambiguous)";
    throw InputError(file_, pointer, "each key once in an object", found);
  }

  std::string file_, base_;
  std::vector<Frame> frames_;
};

// The refusals before parsing: nesting, NUL bytes.
void check_before_parsing(const std::string& text, const std::string& file,
                          const std::string& pointer, const std::string& what) {
  const std::size_t depth = json_nesting_depth(text);
  if (depth > kMaxJsonDepth) {
    throw InputError(file, pointer,
                     what + " nested at most " + std::to_string(kMaxJsonDepth) + " levels deep",
                     "arrays/objects nested " + std::to_string(depth) + " levels deep");
  }
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos) {
    throw InputError(file, pointer, what + " without NUL bytes",
                     "a NUL byte at byte offset " + std::to_string(nul) + " (of " +
                         std::to_string(text.size()) + ")");
  }
}

json parse_checked(const std::string& text, const std::string& file, const std::string& base) {
  return json::parse(text, DuplicateKeyCheck(file, base));
}

}  // namespace

json parse_json_text(const std::string& text, const std::string& file) {
  check_before_parsing(text, file, "", "JSON");
  try {
    return parse_checked(text, file, "");
  } catch (const json::parse_error& e) {
    throw InputError(file, "", "valid JSON", std::string("a syntax error: ") + e.what());
  } catch (const json::exception& e) {
    // A number beyond the double range (1e400) is out_of_range 406, not a parse_error.
    throw InputError(file, "", "valid JSON with finite numbers", e.what());
  }
}

std::optional<json> parse_json_value(const std::string& text, const std::string& origin,
                                     const std::string& base_pointer) {
  check_before_parsing(text, origin, base_pointer, "a value");
  try {
    return parse_checked(text, origin, base_pointer);
  } catch (const json::parse_error&) {
    return std::nullopt;
  } catch (const json::exception&) {
    // Valid JSON syntax that nlohmann cannot hold, e.g. the number 1e400.
    throw InputError(origin, base_pointer, "a finite number", "\"" + text + "\" (number overflow)");
  }
}

}  // namespace pronk::io
