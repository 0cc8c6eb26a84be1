// Counts in messages: singular for exactly one, plural otherwise.
#include <catch2/catch.hpp>

#include "sim/run/count_text.hpp"

namespace count_text_test {

using pronk::run::count_text;

TEST_CASE("count_text: one is singular, others plural", "[count_text]") {
  CHECK(count_text(1, "trial") == "1 trial");
  CHECK(count_text(0, "trial") == "0 trials");
  CHECK(count_text(2, "cell") == "2 cells");
  CHECK(count_text(-1, "step") == "-1 steps");
  CHECK(count_text(12345, "evaluation") == "12345 evaluations");
}

TEST_CASE("count_text: an irregular plural", "[count_text]") {
  CHECK(count_text(1, "analysis", "analyses") == "1 analysis");
  CHECK(count_text(3, "analysis", "analyses") == "3 analyses");
}

}  // namespace count_text_test
