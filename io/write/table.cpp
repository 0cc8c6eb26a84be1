#include "io/write/table.hpp"

#include <charconv>

namespace pronk::io {

namespace {

// Appends x as %.17g. std::to_chars with a precision formats as printf does (C++17
// [charconv.to.chars]), bit for bit, nan and inf included, without printf's locale and
// format parsing.
void append_exact(std::string& out, double x) {
  char buf[32];
  const std::to_chars_result r =
      std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
  out.append(buf, r.ptr);
}

}  // namespace

std::string table_csv(const Table& t) {
  std::string out;
  for (size_t c = 0; c < t.columns.size(); ++c) {
    if (c) out += ',';
    out += t.columns[c];
  }
  out += '\n';
  out.reserve(out.size() + t.data.size() * 24);
  for (size_t r = 0; r < t.rows(); ++r) {
    for (size_t c = 0; c < t.columns.size(); ++c) {
      if (c) out += ',';
      append_exact(out, t.at(r, c));
    }
    out += '\n';
  }
  return out;
}

std::string exact_number(double x) {
  std::string out;
  append_exact(out, x);
  return out;
}

}  // namespace pronk::io
