// The heat maps' gnuplot $boundary datablock: the boundary line breaks at a row where no cell
// stabilized every trial, as report.html's line does.
#include "optimize/map/map_output.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "tests/optimize/map/map_test_support.hpp"

namespace map_output_test {

namespace m = pronk::optimize::map;

m::BoundaryResult row(long r, const std::string& status, double boundary, double first_good) {
  m::BoundaryResult b;
  b.row = r;
  b.status = status;
  b.boundary = boundary;
  b.first_good = first_good;
  return b;
}

/// Four rows of tilt (0, 4, 8, 12 deg) on the tiny map's duty axis.
m::MapStudy four_rows() {
  nlohmann::json doc = pronk::test::tiny_map_document(4, 3, 6.0);
  doc["axes"][1]["values"] = {0, 4, 8, 12};
  return m::parse_map_study(doc, "tiny.json", ".");
}

TEST_CASE("$boundary has a blank line at a none_good row", "[map][map_output]") {
  const m::MapStudy st = four_rows();
  const std::vector<m::BoundaryResult> b = {
      row(0, "bisected", 0.3, 0.2), row(1, "none_good", 0.2, 0.0), row(2, "none_good", 0.2, 0.0),
      row(3, "all_good", 0.4, 0.2)};
  const m::BoundaryBlock block = m::boundary_block(st, b);
  CHECK(block.any);
  CHECK_FALSE(block.band);
  // Rows 1 and 2 make one break (one blank line), between row 0's point and row 3's.
  CHECK_THAT(block.text,
             Catch::Matchers::EndsWith("$boundary << EOD\n0.3 0 0.2\n\n0.4 12 0.2\nEOD\n"));
  const std::string script = m::heatmap_script(st, {}, b, "fraction");
  CHECK(script.find(block.text) != std::string::npos);
  CHECK(script.find("$boundary using 1:2 with linespoints") != std::string::npos);
}

TEST_CASE("$boundary: no blank line before the first boundary, no line when none",
          "[map][map_output]") {
  const m::MapStudy st = four_rows();
  const m::BoundaryBlock lead =
      m::boundary_block(st, {row(0, "none_good", 0.2, 0.0), row(1, "bisected", 0.3, 0.25),
                             row(2, "bisected", 0.35, 0.25), row(3, "none_good", 0.2, 0.0)});
  CHECK(lead.band);
  CHECK_THAT(lead.text, Catch::Matchers::EndsWith("EOD\n0.3 4 0.25\n0.35 8 0.25\n\nEOD\n"));
  std::vector<m::BoundaryResult> none;
  for (long r = 0; r < 4; ++r) none.push_back(row(r, "none_good", 0.2, 0.0));
  const m::BoundaryBlock empty = m::boundary_block(st, none);
  CHECK_FALSE(empty.any);
  CHECK_THAT(empty.text, Catch::Matchers::EndsWith("$boundary << EOD\nEOD\n"));
  CHECK(m::heatmap_script(st, {}, none, "fraction").find("$boundary using") == std::string::npos);
}

}  // namespace map_output_test
