#include "io/page/csv_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "io/load/input_error.hpp"

namespace pronk::io::page {

namespace {

// The fields of `line` (split at commas, every '\r' dropped) into `out`; `scratch` holds the
// line without its '\r's when it has any.
void csvpage_split(std::string_view line, std::string& scratch,
                   std::vector<std::string_view>& out) {
  if (line.find('\r') != std::string_view::npos) {
    scratch.assign(line.begin(), line.end());
    scratch.erase(std::remove(scratch.begin(), scratch.end(), '\r'), scratch.end());
    line = scratch;
  }
  out.clear();
  for (size_t begin = 0;;) {
    const size_t comma = line.find(',', begin);
    out.push_back(line.substr(begin, comma == std::string_view::npos ? comma : comma - begin));
    if (comma == std::string_view::npos) return;
    begin = comma + 1;
  }
}

// strtod's reading of a whole field: a finite number, not out of range (ERANGE, which glibc
// also sets for subnormal numbers).
bool csvpage_strtod(std::string_view s, double& v) {
  const std::string text(s);
  errno = 0;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE && std::isfinite(v);
}

// A finite number spanning the whole field, or nothing: strtod's reading. std::from_chars
// rounds correctly as strtod does, so it reads the plain numbers (what %.17g writes) with the
// same bits; anything else (blanks, a '+', hexadecimal, the ends of the range) goes to strtod.
bool csvpage_number(std::string_view s, double& v) {
  if (s.empty()) return false;
  const std::from_chars_result r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec == std::errc() && r.ptr == s.data() + s.size()) {
    const double a = std::fabs(v);
    if (v == 0.0 || (a > DBL_MIN && a < DBL_MAX)) return true;
  }
  return csvpage_strtod(s, v);
}

// v rounded to `digits` significant digits: the number %.*g prints, read back. to_chars
// with a precision prints as printf does.
double csvpage_round(double v, int digits) {
  if (v == 0.0) return 0.0;
  char buf[32];
  const std::to_chars_result w =
      std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
  double out = 0.0;
  const std::from_chars_result r = std::from_chars(buf, w.ptr, out);
  if (r.ec == std::errc() && r.ptr == w.ptr) return out;
  *w.ptr = '\0';
  return std::strtod(buf, nullptr);
}

// The whole file; empty when it cannot be read.
std::string csvpage_slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  if (in) s << in.rdbuf();
  return s.str();
}

// The next line of `text` from `at` (as std::getline reads it), advancing `at`; false at the end.
bool csvpage_line(const std::string& text, size_t& at, std::string_view& line) {
  if (at >= text.size()) return false;
  const size_t nl = std::min(text.find('\n', at), text.size());
  line = std::string_view(text).substr(at, nl - at);
  at = nl + 1;
  return true;
}

// Appends the fields of data line `n` to the table's columns (see read_csv_table).
void csvpage_row(const std::string& path, long n, const std::vector<std::string_view>& f,
                 bool text_ok, CsvTable& t) {
  if (f.size() != t.columns.size()) {
    throw InputError(path, "line " + std::to_string(n),
                     std::to_string(t.columns.size()) + " fields as in the header",
                     std::to_string(f.size()) + " fields");
  }
  for (size_t c = 0; c < f.size(); ++c) {
    double v = 0.0;
    if (csvpage_number(f[c], v)) {
      t.data[c].push_back(v);
    } else if (text_ok) {
      t.data[c].push_back(f[c].empty() ? nlohmann::json(nullptr)
                                       : nlohmann::json(std::string(f[c])));
    } else {
      throw InputError(path, "line " + std::to_string(n) + ", column " + t.columns[c],
                       "a finite number", "\"" + std::string(f[c].substr(0, 40)) + "\"");
    }
  }
}

// An empty array with room for `n` values.
nlohmann::json csvpage_array(size_t n) {
  nlohmann::json a = nlohmann::json::array();
  a.get_ref<nlohmann::json::array_t&>().reserve(n);
  return a;
}

}  // namespace

CsvTable read_csv_table(const std::string& path, bool text_ok, bool empty_ok) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path, "", "a CSV file written by pronk", "no such file");
  }
  const std::string text = csvpage_slurp(path);
  size_t at = 0;
  std::string_view line;
  if (!csvpage_line(text, at, line) || line.empty()) {
    throw InputError(path, "line 1", "a header line", "an empty file");
  }
  std::string scratch;
  std::vector<std::string_view> fields;
  csvpage_split(line, scratch, fields);
  CsvTable t;
  t.columns.assign(fields.begin(), fields.end());
  const size_t lines = static_cast<size_t>(std::count(text.begin() + at, text.end(), '\n')) + 1;
  for (size_t c = 0; c < t.columns.size(); ++c) t.data.push_back(csvpage_array(lines));
  for (long n = 2; csvpage_line(text, at, line); ++n) {
    if (line.empty() || line == "\r") continue;
    csvpage_split(line, scratch, fields);
    csvpage_row(path, n, fields, text_ok, t);
  }
  if (t.rows() == 0 && !empty_ok) throw InputError(path, "line 2", "at least one data row", "none");
  return t;
}

nlohmann::json sampled_table_json(const CsvTable& table, long max_cells) {
  const long rows = table.rows(), cols = static_cast<long>(table.columns.size());
  const long every = std::max(1L, (rows * cols + max_cells - 1) / std::max(1L, max_cells));
  const auto rounded = [](const nlohmann::json& v, int digits) {
    return v.is_number() ? nlohmann::json(csvpage_round(v.get<double>(), digits)) : v;
  };
  nlohmann::json data = csvpage_array(static_cast<size_t>(cols));
  for (long c = 0; c < cols; ++c) {
    const nlohmann::json::array_t& src =
        table.data[static_cast<size_t>(c)].get_ref<const nlohmann::json::array_t&>();
    const int digits = table.columns[static_cast<size_t>(c)] == "t" ? 9 : 6;
    nlohmann::json col = csvpage_array(static_cast<size_t>(rows / every + 2));
    for (long r = 0; r < rows; r += every) {
      col.push_back(rounded(src[static_cast<size_t>(r)], digits));
      if (r + every >= rows && r != rows - 1) {
        col.push_back(rounded(src[static_cast<size_t>(rows - 1)], digits));
      }
    }
    data.push_back(std::move(col));
  }
  return {{"columns", table.columns}, {"data", std::move(data)}, {"rows", rows}, {"every", every}};
}

}  // namespace pronk::io::page
