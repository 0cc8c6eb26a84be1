// A table of numbers with named columns (row-major): what the CSV outputs hold
// and what the Python module hands out as NumPy arrays, built by one function
// per output so both carry the same bits.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

namespace pronk::io {

struct Table {
  std::vector<std::string> columns;
  std::vector<double> data;  ///< row-major, rows() * columns.size() values

  size_t rows() const { return columns.empty() ? 0 : data.size() / columns.size(); }
  double at(size_t row, size_t col) const { return data[row * columns.size() + col]; }
  void add_row(std::initializer_list<double> values) { data.insert(data.end(), values); }
};

/// CSV text: the header line, then every value as %.17g (every bit kept, so
/// outputs of identical runs are byte-identical).
std::string table_csv(const Table& t);

/// x as %.17g: every bit kept (the CSV and journal outputs' number format).
std::string exact_number(double x);

}  // namespace pronk::io
