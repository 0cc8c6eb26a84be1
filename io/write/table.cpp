#include "io/write/table.hpp"

#include <cstdio>

namespace pronk::io {

std::string table_csv(const Table& t) {
  std::string out;
  for (size_t c = 0; c < t.columns.size(); ++c) {
    if (c) out += ',';
    out += t.columns[c];
  }
  out += '\n';
  out.reserve(out.size() + t.data.size() * 12);
  char buf[32];
  for (size_t r = 0; r < t.rows(); ++r) {
    for (size_t c = 0; c < t.columns.size(); ++c) {
      if (c) out += ',';
      std::snprintf(buf, sizeof buf, "%.17g", t.at(r, c));
      out += buf;
    }
    out += '\n';
  }
  return out;
}

std::string exact_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace pronk::io
