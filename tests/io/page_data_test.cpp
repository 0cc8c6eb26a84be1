// The data behind view.html and report.html: the CSV reader (strict, every field a finite
// number unless text is allowed), the sampling of long tables, and the template filling
// (the data cannot end the script element).
#include <catch2/catch.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/load/input_error.hpp"
#include "io/page/csv_table.hpp"
#include "io/page/html_page.hpp"

using Catch::Matchers::Contains;
using namespace pronk::io;

namespace {

std::string pagedata_write(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace

TEST_CASE("CSV tables of a page are read strictly", "[page]") {
  const std::string ok = pagedata_write("pronk_page_ok.csv", "t,x\n0,1.5\n0.5,-2\n1,3e-3\n");
  const page::CsvTable t = page::read_csv_table(ok);
  REQUIRE(t.columns == std::vector<std::string>{"t", "x"});
  REQUIRE(t.rows() == 3);
  CHECK(t.data[1][2].get<double>() == 3e-3);

  const std::string bad = pagedata_write("pronk_page_bad.csv", "t,x\n0,1\n0.5,abc\n");
  CHECK_THROWS_WITH(page::read_csv_table(bad), Contains("line 3, column x") &&
                                                   Contains("expected a finite number") &&
                                                   Contains("\"abc\""));
  const std::string nan = pagedata_write("pronk_page_nan.csv", "t,x\n0,nan\n");
  CHECK_THROWS_AS(page::read_csv_table(nan), InputError);
  const std::string ragged = pagedata_write("pronk_page_ragged.csv", "t,x\n0,1\n1\n");
  CHECK_THROWS_WITH(page::read_csv_table(ragged), Contains("line 3") && Contains("1 fields"));
  const std::string empty = pagedata_write("pronk_page_empty.csv", "");
  CHECK_THROWS_WITH(page::read_csv_table(empty), Contains("a header line"));
  CHECK_THROWS_WITH(page::read_csv_table("/nonexistent/x.csv"), Contains("no such file"));

  // Text allowed (history.csv, boundary.csv): empty fields are null, words are strings.
  const std::string text = pagedata_write("pronk_page_text.csv", "a,b\n1,\nok,2\n");
  const page::CsvTable tt = page::read_csv_table(text, true);
  CHECK(tt.data[1][0].is_null());
  CHECK(tt.data[0][1] == "ok");
}

TEST_CASE("The page reads numbers as strtod does and rounds them as printf does", "[page]") {
  // The fields strtod reads whole and finite are numbers with strtod's bits; the others
  // (out of range, subnormal, not a number) are text. CRLF line ends, a blank line and a
  // last line without its end are read as before.
  const std::vector<std::string> fields = {"0.10000000000000001",
                                           "-0",
                                           "1.2345678901234567e-05",
                                           " 1.5",
                                           "+2",
                                           "0x10",
                                           "1e400",
                                           "1e-310",
                                           "2.2250738585072014e-308",
                                           "1.7976931348623157e308",
                                           "-nan",
                                           "inf",
                                           "1.",
                                           ".5",
                                           "1e",
                                           "7 ",
                                           "3.0000000000000004",
                                           "abc"};
  std::string text = "t,x\r\n";
  for (size_t i = 0; i < fields.size(); ++i) {
    text += std::to_string(i) + "," + fields[i] + (i == 3 ? "\r\n\n" : "\r\n");
  }
  text += "99,4";  // no line end
  const page::CsvTable t =
      page::read_csv_table(pagedata_write("pronk_page_strtod.csv", text), true);
  REQUIRE(t.columns == std::vector<std::string>{"t", "x"});
  REQUIRE(t.rows() == static_cast<long>(fields.size()) + 1);
  for (size_t i = 0; i < fields.size(); ++i) {
    INFO(fields[i]);
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(fields[i].c_str(), &end);
    const bool number = *end == '\0' && errno != ERANGE && std::isfinite(v);
    const nlohmann::json& got = t.data[1][i];
    REQUIRE(got.is_number() == number);
    if (number) {
      const double g = got.get<double>();
      CHECK(std::memcmp(&g, &v, sizeof v) == 0);
    } else {
      CHECK(got == fields[i]);
    }
  }
  CHECK(t.data[1][fields.size()].get<double>() == 4.0);
  CHECK_THROWS_WITH(
      page::read_csv_table(pagedata_write("pronk_page_blank.csv", "t,x\n0,1\n\n1,x\n")),
      Contains("line 4, column x"));

  // Rounding to 6 significant digits (time: 9) is printf's %.*g read back with strtod.
  page::CsvTable r;
  r.columns = {"t", "x"};
  r.data = {nlohmann::json::array(), nlohmann::json::array()};
  std::vector<double> values = {1e-300, 5e-324, -0.0, 1.0 / 3.0, 123456.5, 999999.5, 1e300};
  for (int i = 0; i < 2000; ++i)
    values.push_back(std::ldexp(1.0 + i * 0.618033988749895, i % 200 - 100) * (i % 2 ? -1 : 1));
  for (double v : values) {
    r.data[0].push_back(v);
    r.data[1].push_back(v);
  }
  const nlohmann::json j = page::sampled_table_json(r, 1L << 40);
  for (size_t i = 0; i < values.size(); ++i) {
    for (int c : {0, 1}) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.*g", c == 0 ? 9 : 6, values[i]);
      const double expected = values[i] == 0.0 ? 0.0 : std::strtod(buf, nullptr);
      const double got = j["data"][c][i].get<double>();
      INFO(buf);
      CHECK(std::memcmp(&got, &expected, sizeof got) == 0);
    }
  }
}

TEST_CASE("Long tables are thinned to the page's budget, keeping the last row", "[page]") {
  page::CsvTable t;
  t.columns = {"t", "x"};
  t.data = {nlohmann::json::array(), nlohmann::json::array()};
  for (int i = 0; i < 1001; ++i) {
    t.data[0].push_back(i * 0.01);
    t.data[1].push_back(1.0 / 3.0 + i);
  }
  // 2002 numbers in a budget of 500: every 5th row (ceil(2002 / 500)), then the last.
  const nlohmann::json j = page::sampled_table_json(t, 500);
  CHECK(j["every"] == 5);
  CHECK(j["rows"] == 1001);
  REQUIRE(j["data"][0].size() == 201);  // rows 0, 5, ..., 1000
  CHECK(j["data"][0].back().get<double>() == Approx(10.0));
  // Rounded to 6 significant digits (time: 9).
  CHECK(j["data"][1][0].get<double>() == 0.333333);
  // Within the budget: every row, unchanged count.
  CHECK(page::sampled_table_json(t, 1 << 20)["data"][0].size() == 1001);
  // A table whose last row falls between samples still ends at it.
  const nlohmann::json k = page::sampled_table_json(t, 600);  // every 4th: 0..1000 ends on it
  CHECK(k["data"][0].back().get<double>() == Approx(10.0));
  const nlohmann::json m = page::sampled_table_json(t, 2002 / 3 + 1);  // every 3rd: 999, then 1000
  CHECK(m["data"][0].size() == 335);
  CHECK(m["data"][0].back().get<double>() == Approx(10.0));
}

TEST_CASE("The page data fills the template and cannot close its script element", "[page]") {
  const nlohmann::json data = {{"name", "</script><script>alert(1)</script>"}, {"x", 1.5}};
  const std::string html = page::fill_template("<a>@PRONK_DATA@</a>", data);
  CHECK(html.find("</script>") == std::string::npos);
  // Between the tags: JSON that parses back to the same data.
  const std::string inner = html.substr(3, html.size() - 7);
  CHECK(nlohmann::json::parse(inner) == data);
  CHECK_THROWS_AS(page::fill_template("<a></a>", data), std::logic_error);
}
