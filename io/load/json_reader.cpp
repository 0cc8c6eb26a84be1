#include "io/load/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pronk::io {

std::string describe(const json& v) {
  std::string dumped = v.dump(-1, ' ', true, json::error_handler_t::replace);
  if (dumped.size() > 60) dumped = dumped.substr(0, 57) + "...";
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "boolean " + dumped;
    case json::value_t::string:
      return "string " + dumped;
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "number " + dumped;
    case json::value_t::array:
      return "array of " + std::to_string(v.size()) + " element(s) " + dumped;
    case json::value_t::object:
      return "object " + dumped;
    default:
      return dumped;
  }
}

std::string pointer_escape(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

namespace {

// Decodes one reference token (~1 is '/', ~0 is '~'); false for any other '~' escape.
bool unescape_token(const std::string& raw, std::string* token) {
  token->clear();
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '~') {
      *token += raw[i];
    } else if (i + 1 < raw.size() && (raw[i + 1] == '0' || raw[i + 1] == '1')) {
      *token += raw[++i] == '0' ? '~' : '/';
    } else {
      return false;
    }
  }
  return true;
}

// An array index token: "0" or a decimal without a leading zero, below `size`.
bool array_index(const std::string& token, std::size_t size, std::size_t* index) {
  if (token.empty() || token.size() > 18 || (token.size() > 1 && token[0] == '0')) return false;
  if (!std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return false;
  }
  *index = static_cast<std::size_t>(std::stoull(token));
  return *index < size;
}

}  // namespace

const json* find_pointer(const json& doc, const std::string& pointer) {
  if (pointer.empty()) return &doc;
  if (pointer[0] != '/') return nullptr;
  const json* at = &doc;
  std::string token;
  std::size_t begin = 1;
  while (true) {
    const std::size_t end = std::min(pointer.find('/', begin), pointer.size());
    if (!unescape_token(pointer.substr(begin, end - begin), &token)) return nullptr;
    std::size_t index = 0;
    if (at->is_object()) {
      const auto it = at->find(token);
      if (it == at->end()) return nullptr;
      at = &*it;
    } else if (at->is_array() && array_index(token, at->size(), &index)) {
      at = &(*at)[index];
    } else {
      return nullptr;
    }
    if (end == pointer.size()) return at;
    begin = end + 1;
  }
}

json* find_pointer(json& doc, const std::string& pointer) {
  return const_cast<json*>(find_pointer(static_cast<const json&>(doc), pointer));
}

std::string path_name_problem(const std::string& name) {
  if (name.empty()) return "an empty name";
  if (name == "." || name == "..") return "\"" + name + "\", which names a directory itself";
  if (name.size() > kMaxPathNameBytes) {
    return "a name of " + std::to_string(name.size()) + " bytes";
  }
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c == '/') return "\"" + name + "\", which has a '/'";
    if (c < 0x20 || c == 0x7f) {
      return "a control character (byte " + std::to_string(c) + ") at byte " + std::to_string(i);
    }
  }
  return "";
}

namespace {
std::string number_text(double x) {
  std::ostringstream s;
  s.precision(12);
  s << x;
  return s.str();
}
std::string range_text(double lo, double hi) {
  if (std::isinf(lo) && std::isinf(hi)) return "a finite number";
  if (std::isinf(hi)) return "a finite number >= " + number_text(lo);
  if (std::isinf(lo)) return "a finite number <= " + number_text(hi);
  return "a finite number in [" + number_text(lo) + ", " + number_text(hi) + "]";
}
}  // namespace

JsonReader::JsonReader(const json& node, std::string file, std::string pointer)
    : node_(&node), file_(std::move(file)), pointer_(std::move(pointer)) {
  if (!node.is_object()) throw InputError(file_, pointer_, "an object", describe(node));
}

std::string JsonReader::pointer_of(const std::string& key) const {
  return pointer_ + "/" + pointer_escape(key);
}

InputError JsonReader::error(const std::string& key, const std::string& expected,
                             const std::string& found) const {
  return InputError(file_, key.empty() ? pointer_ : pointer_of(key), expected, found);
}

bool JsonReader::has(const std::string& key) const { return node_->contains(key); }

const json& JsonReader::get(const std::string& key) {
  read_.insert(key);
  auto it = node_->find(key);
  if (it == node_->end()) throw error(key, "a value (required key)", "nothing");
  return *it;
}

JsonReader JsonReader::object(const std::string& key) {
  return JsonReader(get(key), file_, pointer_of(key));
}

std::vector<JsonReader> JsonReader::object_array(const std::string& key) {
  const json& a = get(key);
  if (!a.is_array()) throw error(key, "an array of objects", describe(a));
  std::vector<JsonReader> out;
  for (size_t i = 0; i < a.size(); ++i) {
    out.emplace_back(a[i], file_, pointer_of(key) + "/" + std::to_string(i));
  }
  return out;
}

static double checked_number(const JsonReader& r, const std::string& ptr_key, const json& v,
                             double lo, double hi, const std::string& pointer) {
  (void)ptr_key;
  if (std::isinf(lo)) lo = -kMaxInputMagnitude;
  if (std::isinf(hi)) hi = kMaxInputMagnitude;
  if (!v.is_number()) throw InputError(r.file(), pointer, range_text(lo, hi), describe(v));
  double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    throw InputError(r.file(), pointer, range_text(lo, hi), describe(v));
  }
  return x;
}

double JsonReader::number(const std::string& key, double lo, double hi) {
  return checked_number(*this, key, get(key), lo, hi, pointer_of(key));
}

double JsonReader::number_or(const std::string& key, double fallback, double lo, double hi) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  return number(key, lo, hi);
}

double JsonReader::positive_or(const std::string& key, double fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = get(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0.0 ||
      v.get<double>() > kMaxInputMagnitude) {
    throw error(key, "a finite number > 0 and <= " + number_text(kMaxInputMagnitude), describe(v));
  }
  return v.get<double>();
}

long JsonReader::integer_or(const std::string& key, long fallback, long lo, long hi) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = get(key);
  std::string expected = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!v.is_number_integer()) {
    // Accept 3.0 style numbers that are exact integers.
    if (v.is_number_float()) {
      double d = v.get<double>();
      if (std::isfinite(d) && d == std::floor(d) && d >= static_cast<double>(lo) &&
          d <= static_cast<double>(hi)) {
        return static_cast<long>(d);
      }
    }
    throw error(key, expected, describe(v));
  }
  long x = 0;
  if (v.is_number_unsigned()) {
    auto u = v.get<unsigned long long>();
    if (u > static_cast<unsigned long long>(hi)) throw error(key, expected, describe(v));
    x = static_cast<long>(u);
  } else {
    x = v.get<long>();
  }
  if (x < lo || x > hi) throw error(key, expected, describe(v));
  return x;
}

bool JsonReader::boolean_or(const std::string& key, bool fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = get(key);
  if (!v.is_boolean()) throw error(key, "true or false", describe(v));
  return v.get<bool>();
}

std::string JsonReader::string_or(const std::string& key, const std::string& fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = get(key);
  if (!v.is_string()) throw error(key, "a string", describe(v));
  return v.get<std::string>();
}

std::string JsonReader::path_name_or(const std::string& key, const std::string& fallback) {
  const std::string name = string_or(key, fallback);
  const std::string problem = path_name_problem(name);
  if (!problem.empty()) {
    throw error(key,
                "a name usable as a directory name (not empty, \".\" or \"..\"; no '/', no "
                "control characters; at most " +
                    std::to_string(kMaxPathNameBytes) + " bytes)",
                problem);
  }
  return name;
}

std::string JsonReader::choice_or(const std::string& key, const std::string& fallback,
                                  std::initializer_list<const char*> choices) {
  return choice_or(key, fallback, std::vector<std::string>(choices.begin(), choices.end()));
}

std::string JsonReader::choice_or(const std::string& key, const std::string& fallback,
                                  const std::vector<std::string>& choices) {
  std::string expected = "one of";
  for (const std::string& c : choices) expected += " \"" + c + "\"";
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = get(key);
  if (v.is_string()) {
    for (const std::string& c : choices) {
      if (v.get<std::string>() == c) return c;
    }
  }
  throw error(key, expected, describe(v));
}

Eigen::VectorXd JsonReader::vector(const std::string& key, int n, double lo, double hi) {
  const json& v = get(key);
  std::string expected = "an array of " + std::to_string(n) + " numbers";
  if (!v.is_array() || static_cast<int>(v.size()) != n) throw error(key, expected, describe(v));
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) {
    out[i] = checked_number(*this, key, v[i], lo, hi, pointer_of(key) + "/" + std::to_string(i));
  }
  return out;
}

Eigen::Vector3d JsonReader::vec3_or(const std::string& key, const Eigen::Vector3d& fallback) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  return vector(key, 3);
}

std::vector<long> JsonReader::integer_array_or(const std::string& key, long lo, long hi) {
  std::vector<long> out;
  if (!has(key)) {
    read_.insert(key);
    return out;
  }
  const json& v = get(key);
  std::string expected =
      "an array of integers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!v.is_array()) throw error(key, expected, describe(v));
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number_integer() || v[i].get<long>() < lo || v[i].get<long>() > hi) {
      throw InputError(file_, pointer_of(key) + "/" + std::to_string(i), expected.substr(12),
                       describe(v[i]));
    }
    out.push_back(v[i].get<long>());
  }
  return out;
}

Eigen::MatrixXd JsonReader::matrix(const std::string& key, int rows, int cols) {
  const json& v = get(key);
  const std::string expected =
      "an array of " + std::to_string(rows) + " rows of " + std::to_string(cols) + " numbers";
  if (!v.is_array() || static_cast<int>(v.size()) != rows) throw error(key, expected, describe(v));
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i) {
    const std::string row_ptr = pointer_of(key) + "/" + std::to_string(i);
    if (!v[i].is_array() || static_cast<int>(v[i].size()) != cols) {
      throw InputError(file_, row_ptr, "an array of " + std::to_string(cols) + " numbers",
                       describe(v[i]));
    }
    for (int j = 0; j < cols; ++j) {
      m(i, j) = checked_number(*this, key, v[i][j], -std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::infinity(),
                               row_ptr + "/" + std::to_string(j));
    }
  }
  return m;
}

std::vector<Eigen::Vector3d> JsonReader::vec3_list(const std::string& key, size_t min_n,
                                                   size_t max_n) {
  const json& v = get(key);
  const std::string expected =
      "an array of " + std::to_string(min_n) + ".." + std::to_string(max_n) + " points [x, y, z]";
  if (!v.is_array() || v.size() < min_n || v.size() > max_n)
    throw error(key, expected, describe(v));
  Eigen::MatrixXd m = matrix(key, static_cast<int>(v.size()), 3);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < m.rows(); ++i) out.emplace_back(m.row(i).transpose());
  return out;
}

std::vector<std::vector<int>> JsonReader::index_groups(const std::string& key, long max_index) {
  const json& v = get(key);
  const std::string expected =
      "an array of non-empty arrays of leg indices in [0, " + std::to_string(max_index) + "]";
  if (!v.is_array() || v.empty()) throw error(key, expected, describe(v));
  std::vector<std::vector<int>> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string gp = pointer_of(key) + "/" + std::to_string(i);
    if (!v[i].is_array() || v[i].empty()) throw InputError(file_, gp, expected, describe(v[i]));
    std::vector<int> group;
    for (size_t j = 0; j < v[i].size(); ++j) {
      const json& e = v[i][j];
      if (!e.is_number_integer() || e.get<long>() < 0 || e.get<long>() > max_index ||
          std::find(group.begin(), group.end(), e.get<int>()) != group.end()) {
        throw InputError(file_, gp + "/" + std::to_string(j),
                         "a distinct leg index in [0, " + std::to_string(max_index) + "]",
                         describe(e));
      }
      group.push_back(e.get<int>());
    }
    out.push_back(group);
  }
  return out;
}

void JsonReader::finish() const {
  for (auto it = node_->begin(); it != node_->end(); ++it) {
    if (read_.count(it.key()) == 0) {
      std::string known;
      for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
      throw InputError(file_, pointer_of(it.key()), "a known key (" + known + ")",
                       "unknown key \"" + it.key() + "\"");
    }
  }
}

}  // namespace pronk::io
