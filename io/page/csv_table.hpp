// Reads a CSV file that pronk wrote (a header line, then rows of the same length) into
// columns for a page: every field a finite number, or (where allowed) empty or text.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::io::page {

struct CsvTable {
  std::vector<std::string> columns;
  /// data[c][r]: numbers, or null (empty field) and strings where the reader allows them.
  std::vector<nlohmann::json> data;
  long rows() const { return data.empty() ? 0 : static_cast<long>(data[0].size()); }
};

/// Reads `path`. InputError (file, "line N" or "line N, column NAME", expected, found) for a
/// missing or empty file, no data rows, a row of another length, a field that is not a finite
/// number (unless `text_ok`: then empty fields are null and other text is kept as a string),
/// no data row (unless `empty_ok`: strides.csv of a run that fell before its first touchdown).
CsvTable read_csv_table(const std::string& path, bool text_ok = false, bool empty_ok = false);

/// The table as page JSON {columns, data, rows, every}: every `every`-th row (and the last
/// row) with at most `max_cells` numbers in all; numbers rounded to 6 significant digits
/// (time column "t": 9), which is far below what a page can draw.
nlohmann::json sampled_table_json(const CsvTable& table, long max_cells);

}  // namespace pronk::io::page
