// The sentences `pronk map` prints: every branch of the disagreement sentence and of a row's
// boundary (a row with no good cell names no value).
#include "app/map_report_text.hpp"

#include <catch2/catch.hpp>

namespace map_report_text_test {

using nlohmann::json;
namespace m = pronk::optimize::map;

TEST_CASE("the disagreement sentence in each case", "[cli][map][map_report_text]") {
  using pronk::app::disagreement_sentence;
  CHECK(disagreement_sentence({{"first_disagreement", nullptr}, {"no_disagreement_up_to", 0.4}},
                              "duty_cycle") == "none anywhere on the grid (duty_cycle up to 0.4)");
  CHECK(disagreement_sentence({{"first_disagreement", 0.05}, {"no_disagreement_up_to", nullptr}},
                              "duty_cycle") ==
        "the first already at the grid's first duty_cycle = 0.05");
  CHECK(disagreement_sentence({{"first_disagreement", 0.3}, {"no_disagreement_up_to", 0.25}},
                              "duty_cycle") == "none up to duty_cycle = 0.25, the first at 0.3");
}

TEST_CASE("the boundary sentence: a value unless no cell was good", "[cli][map][map_report_text]") {
  m::BoundaryResult b;
  b.row = 2;
  b.boundary = 0.28812345;
  b.status = "bisected";
  CHECK(pronk::app::boundary_sentence(b, "duty_cycle") ==
        "boundary row 2: bisected duty_cycle = 0.288123");
  b.status = "all_good";
  b.boundary = 0.4;
  CHECK(pronk::app::boundary_sentence(b, "duty_cycle") ==
        "boundary row 2: all_good duty_cycle = 0.4");
  b.status = "none_good";
  b.boundary = 0.05;
  const std::string none = pronk::app::boundary_sentence(b, "duty_cycle");
  CHECK(none == "boundary row 2: none_good: no duty_cycle on the grid stabilized every trial");
  CHECK(none.find("0.05") == std::string::npos);
}

}  // namespace map_report_text_test
