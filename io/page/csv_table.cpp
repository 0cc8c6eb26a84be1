#include "io/page/csv_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/load/input_error.hpp"

namespace pronk::io::page {

namespace {

std::vector<std::string> csvpage_split(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// A finite number spanning the whole field, or nothing.
bool csvpage_number(const std::string& s, double& v) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && errno != ERANGE && std::isfinite(v);
}

double csvpage_round(double v, int digits) {
  if (v == 0.0) return 0.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return std::strtod(buf, nullptr);
}

}  // namespace

CsvTable read_csv_table(const std::string& path, bool text_ok, bool empty_ok) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path, "", "a CSV file written by pronk", "no such file");
  }
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line.empty()) {
    throw InputError(path, "line 1", "a header line", "an empty file");
  }
  CsvTable t;
  t.columns = csvpage_split(line);
  t.data.assign(t.columns.size(), nlohmann::json::array());
  long n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> f = csvpage_split(line);
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
        t.data[c].push_back(f[c].empty() ? nlohmann::json(nullptr) : nlohmann::json(f[c]));
      } else {
        throw InputError(path, "line " + std::to_string(n) + ", column " + t.columns[c],
                         "a finite number", "\"" + f[c].substr(0, 40) + "\"");
      }
    }
  }
  if (t.rows() == 0 && !empty_ok) throw InputError(path, "line 2", "at least one data row", "none");
  return t;
}

nlohmann::json sampled_table_json(const CsvTable& table, long max_cells) {
  const long rows = table.rows(), cols = static_cast<long>(table.columns.size());
  const long every = std::max(1L, (rows * cols + max_cells - 1) / std::max(1L, max_cells));
  nlohmann::json data = nlohmann::json::array();
  for (long c = 0; c < cols; ++c) {
    const nlohmann::json& src = table.data[static_cast<size_t>(c)];
    const int digits = table.columns[static_cast<size_t>(c)] == "t" ? 9 : 6;
    nlohmann::json col = nlohmann::json::array();
    for (long r = 0; r < rows; r += every) {
      const nlohmann::json& v = src[static_cast<size_t>(r)];
      col.push_back(v.is_number() ? nlohmann::json(csvpage_round(v.get<double>(), digits)) : v);
      if (r + every >= rows && r != rows - 1) {
        const nlohmann::json& last = src[static_cast<size_t>(rows - 1)];
        col.push_back(last.is_number() ? nlohmann::json(csvpage_round(last.get<double>(), digits))
                                       : last);
      }
    }
    data.push_back(std::move(col));
  }
  return {{"columns", table.columns}, {"data", std::move(data)}, {"rows", rows}, {"every", every}};
}

}  // namespace pronk::io::page
