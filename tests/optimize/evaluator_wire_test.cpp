// The evaluator's wire format (optimize/evaluator_wire.hpp): a configuration and
// a job's outcome survive the JSON round trip bit for bit, non-finite values
// included, so a job computed on another MPI rank equals one computed here.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "optimize/evaluator_wire.hpp"
#include "optimize/study.hpp"

using namespace pronk::optimize;

TEST_CASE("evaluator wire: a configuration round trip computes the same jobs bit for bit",
          "[optimize][wire]") {
  const Study st =
      load_study(std::string(PRONK_SOURCE_DIR) + "/studies/study1_body_only_gains.json",
                 {"/scenarios/random/count=3", "/scenarios/duration=1"});
  const EvaluatorConfig back = evaluator_config_from_wire(
      nlohmann::json::parse(evaluator_config_to_wire(st.evaluator).dump()));
  REQUIRE(back.scenarios.scenarios.size() == 3);
  CHECK(back.scenarios.scenarios[2].tilt == st.evaluator.scenarios.scenarios[2].tilt);
  CHECK(back.scenarios.scenarios[1].velocity_kick ==
        st.evaluator.scenarios.scenarios[1].velocity_kick);
  const Evaluator here(st.evaluator), there(back);
  std::vector<double> job{0.0};
  for (double u : here.initial_point()) job.push_back(u * 0.9 + 0.03);
  for (long i = 0; i <= 3; ++i) {
    job[0] = static_cast<double>(i);
    INFO("job " << i);
    CHECK(here.compute_job(job).dump() == there.compute_job(job).dump());
  }
}

TEST_CASE("evaluator wire: job outcomes keep non-finite metrics and errors", "[optimize][wire]") {
  JobOutcome o;
  o.stability.ok = true;
  o.stability.spectral_radius = 0.1 + 0.2;  // not a short decimal
  o.stability.method = "orbit_jacobian";
  o.scenario.name = "random_1";
  o.scenario.metrics = {{"a", std::numeric_limits<double>::infinity()},
                        {"b", -std::numeric_limits<double>::infinity()},
                        {"c", std::numeric_limits<double>::quiet_NaN()},
                        {"d", 1.0 / 3.0}};
  o.scenario.strides = 17;
  const JobOutcome r = job_outcome_from_wire(nlohmann::json::parse(job_outcome_to_wire(o).dump()));
  CHECK(r.error.empty());
  CHECK(r.stability.spectral_radius == o.stability.spectral_radius);
  CHECK(r.stability.method == "orbit_jacobian");
  CHECK(r.scenario.metrics.at("a") == std::numeric_limits<double>::infinity());
  CHECK(r.scenario.metrics.at("b") == -std::numeric_limits<double>::infinity());
  CHECK(std::isnan(r.scenario.metrics.at("c")));
  CHECK(r.scenario.metrics.at("d") == 1.0 / 3.0);
  CHECK(r.scenario.strides == 17);
  JobOutcome e;
  e.error = "boom";
  CHECK(job_outcome_from_wire(job_outcome_to_wire(e)).error == "boom");
  CHECK(!job_outcome_from_wire(nlohmann::json::parse(R"({"stability": 3})")).error.empty());
}
