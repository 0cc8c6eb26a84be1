// pagmo driver: every algorithm on analytic problems with known minima, constraints as a
// penalty, one batch per generation, the budget in whole generations, determinism over
// thread counts and seeds, tolerances, the stop flag, and the option checks.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "optimize/optimizer.hpp"
#include "optimize/pagmo_driver.hpp"
#include "tests/optimize/driver_test_problems.hpp"

using namespace pronk::optimize;
using namespace pronk::optimize::test;
using nlohmann::json;

namespace {

struct PagmoCase {
  const char* name;
  long population;
  long budget;
  double tolerance;  ///< on |x - x*|
};

/// The algorithms the driver offers, with a budget that reaches the tolerance.
const std::vector<PagmoCase> kPagmoAlgorithms = {
    {"cmaes", 12, 3000, 1e-4}, {"xnes", 12, 3000, 1e-4},   {"de", 20, 4000, 1e-3},
    {"sade", 20, 4000, 1e-3},  {"de1220", 20, 4000, 1e-3}, {"pso_gen", 20, 4000, 1e-2},
};

OptimizerOptions pagmo_options(const std::string& algorithm, json options, long budget) {
  OptimizerOptions o;
  o.library = "pagmo";
  o.algorithm = algorithm;
  o.pagmo_options = std::move(options);
  o.max_evaluations = budget;
  o.seed = 3;
  return o;
}

/// Evaluations in input order, and the size of every evaluate_batch call.
class CountingProblem : public LambdaProblem {
 public:
  using LambdaProblem::LambdaProblem;
  std::vector<ProblemEvaluation> evaluate_batch(
      const std::vector<std::vector<double>>& xs) const override {
    {
      std::lock_guard<std::mutex> lock(m_);
      batches.push_back(static_cast<long>(xs.size()));
    }
    return LambdaProblem::evaluate_batch(xs);
  }
  mutable std::vector<long> batches;

 private:
  mutable std::mutex m_;
};

CountingProblem counting_quadratic(int n) {
  return CountingProblem(std::vector<double>(static_cast<std::size_t>(n), -3.0),
                         std::vector<double>(static_cast<std::size_t>(n), 3.0),
                         std::vector<double>(static_cast<std::size_t>(n), -2.0), 0, quadratic_at);
}

/// The observer saw every evaluation once, in index order, and the result's best is one of them.
void check_pagmo_observed(const Recorder& rec, const OptimizerResult& r) {
  REQUIRE(static_cast<long>(rec.seen.size()) == r.evaluations);
  for (std::size_t i = 0; i < rec.seen.size(); ++i) REQUIRE(rec.seen[i].index == long(i));
  REQUIRE(r.best_index >= 0);
  const Observed& b = rec.seen[static_cast<std::size_t>(r.best_index)];
  CHECK(b.x == r.best_x);
  CHECK(b.e.cost == r.best_cost);
}

std::string validation_error(const std::string& algorithm, const json& options,
                             long max_evaluations = 1000) {
  std::string error;
  CHECK_FALSE(validate_pagmo_options(algorithm, options, max_evaluations, &error));
  return error;
}

}  // namespace

TEST_CASE("pagmo algorithms find the minima of the shifted quadratic and of Rosenbrock",
          "[optimize][pagmo]") {
  for (const auto& c : kPagmoAlgorithms) {
    SECTION(c.name) {
      const auto o = pagmo_options(c.name, {{"population", c.population}}, c.budget);
      const auto q = shifted_quadratic(3);
      Recorder rec;
      const OptimizerResult rq = run_optimizer(q, o, &rec);
      INFO(rq.message);
      CHECK(rq.library == "pagmo");
      CHECK(rq.algorithm == c.name);
      CHECK(rq.best_feasible);
      CHECK(distance(rq.best_x, {1.0, -0.5, 0.25}) < c.tolerance);
      CHECK(rq.best_cost < c.tolerance * c.tolerance);
      check_pagmo_observed(rec, rq);
      CHECK(rec.seen.front().x == q.initial_point());  // the start is in the first population

      const OptimizerResult rr = run_optimizer(rosenbrock(), o);
      INFO(rr.message);
      CHECK(distance(rr.best_x, {1.0, 1.0}) < 10 * c.tolerance);
    }
  }
}

TEST_CASE("pagmo: constraints become the quadratic penalty and the result says so",
          "[optimize][pagmo]") {
  // min x^2 + y^2 s.t. x + y >= 1: (0.5, 0.5), cost 0.5. With the penalty w (1 - x - y)^2
  // the minimum is x = y = w / (1 + 2 w), slightly infeasible: the population converges
  // there, and the result is the best feasible evaluation, near (0.5, 0.5).
  Recorder rec;
  const auto r =
      run_optimizer(constrained_circle(), pagmo_options("cmaes", {{"population", 12}}, 3000), &rec);
  INFO(r.message);
  CHECK(r.constraints_as_penalty);
  CHECK(r.message.find("quadratic penalty (weight 1000)") != std::string::npos);
  const double t = 1000.0 / (1.0 + 2000.0);
  CHECK(distance(rec.seen.back().x, {t, t}) < 1e-4);
  CHECK(r.best_feasible);
  CHECK(r.best_constraints[0] <= 0.0);
  CHECK(distance(r.best_x, {0.5, 0.5}) < 1e-2);
  CHECK(std::abs(r.best_cost - 0.5) < 1e-2);
}

TEST_CASE("pagmo: every generation is one batch and the budget holds whole generations",
          "[optimize][pagmo]") {
  for (const auto& c : kPagmoAlgorithms) {
    SECTION(c.name) {
      const auto p = counting_quadratic(4);
      const OptimizerResult r = run_optimizer(p, pagmo_options(c.name, {{"population", 10}}, 95));
      INFO(r.message);
      CHECK(r.evaluations == 90);  // the first population and 8 generations of 10
      CHECK(r.status == OptimizerStatus::kMaxEvaluations);
      CHECK(p.batches == std::vector<long>(9, 10));
      CHECK(r.message.find("8 generation(s) after the first") != std::string::npos);
      CHECK(r.message.find("unused") == std::string::npos);

      const auto capped = counting_quadratic(4);
      const OptimizerResult rc = run_optimizer(
          capped, pagmo_options(c.name, {{"population", 10}, {"generations", 3}}, 95));
      CHECK(rc.evaluations == 40);
      CHECK(rc.status == OptimizerStatus::kMaxEvaluations);
      CHECK(rc.library_status == "generations");
    }
  }
  SECTION("self-adaptation variant 2 of sade and de1220: point by point, to the last evaluation") {
    for (const char* name : {"sade", "de1220"}) {
      const auto p = counting_quadratic(4);
      const OptimizerResult r =
          run_optimizer(p, pagmo_options(name, {{"population", 10}, {"variant_adptv", 2}}, 95));
      INFO(name << ": " << r.message);
      CHECK(r.evaluations == 95);
      CHECK(p.batches.front() == 10);
      CHECK(p.batches.size() == 86);  // then 85 batches of one point
      CHECK(r.message.find("unused") == std::string::npos);
    }
  }
}

TEST_CASE("pagmo: the same evaluations whatever the thread count; the seed changes them",
          "[optimize][pagmo][determinism]") {
  for (const auto& c : kPagmoAlgorithms) {
    SECTION(c.name) {
      auto run = [&](int threads, unsigned long long seed) {
        auto p = shifted_quadratic(3);
        p.threads = threads;
        auto o = pagmo_options(c.name, {{"population", 10}}, 200);
        o.seed = seed;
        Recorder rec;
        (void)run_optimizer(p, o, &rec);
        return rec.seen;
      };
      const auto a = run(1, 5), b = run(3, 5), other = run(1, 6);
      REQUIRE(a.size() == b.size());
      bool same = true;
      for (std::size_t i = 0; i < a.size(); ++i)
        same = same && a[i].x == b[i].x && a[i].e.cost == b[i].e.cost;
      CHECK(same);
      REQUIRE(other.size() > 1);
      CHECK(other[1].x != a[1].x);
    }
  }
}

TEST_CASE("pagmo: xtol and ftol end a run as converged; the stop flag ends it as stopped",
          "[optimize][pagmo]") {
  SECTION("xtol") {
    const auto r = run_optimizer(
        shifted_quadratic(2), pagmo_options("cmaes", {{"population", 10}, {"xtol", 1e-3}}, 5000));
    CHECK(r.status == OptimizerStatus::kConverged);
    CHECK(r.library_status == "xtol");
    CHECK(r.evaluations < 5000);
    CHECK(distance(r.best_x, {1.0, -0.5}) < 1e-3);
  }
  SECTION("ftol") {
    const auto r = run_optimizer(shifted_quadratic(2),
                                 pagmo_options("de", {{"population", 10}, {"ftol", 1e-8}}, 5000));
    CHECK(r.status == OptimizerStatus::kConverged);
    CHECK(r.library_status == "ftol");
    CHECK(r.best_cost < 1e-6);
  }
  for (const char* name : {"cmaes", "pso_gen"}) {
    SECTION(std::string("stop flag, ") + name) {
      std::atomic<bool> stop{false};
      Recorder rec;
      rec.flag = &stop;
      rec.stop_after = 25;
      auto o = pagmo_options(name, {{"population", 10}}, 1000);
      o.stop_flag = &stop;
      const auto r = run_optimizer(shifted_quadratic(2), o, &rec);
      CHECK(r.status == OptimizerStatus::kStopped);
      CHECK(r.evaluations == 30);  // the batch under way when the flag was set completes
      check_pagmo_observed(rec, r);
    }
  }
}

TEST_CASE("pagmo: unbounded variables are a failure, not a crash", "[optimize][pagmo]") {
  const double inf = std::numeric_limits<double>::infinity();
  LambdaProblem p({-inf, 0.0}, {inf, 1.0}, {0.0, 0.5}, 0, quadratic_at);
  const auto r = run_optimizer(p, pagmo_options("cmaes", {{"population", 10}}, 100));
  CHECK(r.status == OptimizerStatus::kFailed);
  CHECK(r.evaluations == 0);
  CHECK(r.message.find("finite bounds") != std::string::npos);
}

TEST_CASE("pagmo options: unknown names, bad values and too small populations are refused",
          "[optimize][pagmo][input]") {
  CHECK(is_pagmo_algorithm("cmaes"));
  CHECK(is_pagmo_algorithm("pso_gen"));
  CHECK_FALSE(is_pagmo_algorithm("pso"));
  std::string error;
  CHECK(validate_pagmo_options("cmaes", json::object(), 20, &error));
  CHECK(validate_pagmo_options("de1220", {{"allowed_variants", {1, 18}}, {"xtol", 0}}, 20, &error));

  CHECK(validation_error("nsga3", json::object()) ==
        "algorithm: \"nsga3\": expected a pagmo algorithm pronk offers (cmaes, xnes, de, sade, "
        "de1220, pso_gen)");
  CHECK_THAT(validation_error("pso", json::object()),
             Catch::Contains("pso_gen is its generational form"));
  CHECK(validation_error("cmaes", {{"sigma", 0.3}}) ==
        "options/sigma: an unknown option: expected an option of pagmo cmaes (population, "
        "generations, ftol, xtol, sigma0, cc, cs, c1, cmu)");
  CHECK(validation_error("pso_gen", {{"ftol", 1e-6}}).rfind("options/ftol: an unknown option", 0) ==
        0);
  CHECK(validation_error("cmaes", {{"population", 4}}) ==
        "options/population: 4: expected a population of at least 5 (pagmo cmaes needs at "
        "least 5 individuals)");
  CHECK_THAT(validation_error("xnes", {{"population", 4}}), Catch::Contains("at least 5"));
  CHECK_THAT(validation_error("de", {{"population", 4}}), Catch::Contains("at least 5"));
  CHECK_THAT(validation_error("sade", {{"population", 6}}), Catch::Contains("at least 7"));
  CHECK_THAT(validation_error("de1220", {{"population", 6}}), Catch::Contains("at least 7"));
  CHECK(validation_error("pso_gen", {{"population", 5}, {"neighb_param", 10}}) ==
        "options/population: 5: expected a population of at least 6 (the ring topology of "
        "pso_gen (neighb_type 2) links neighb_param / 2 = 5 particles on each side)");
  CHECK(validate_pagmo_options(
      "pso_gen", {{"population", 5}, {"neighb_param", 10}, {"neighb_type", 1}}, 20, &error));
  CHECK(validation_error("cmaes", {{"population", 40}}, 30) ==
        "options/population: 40: expected at most max_evaluations = 30 (the first population "
        "alone takes that many evaluations)");
  CHECK(validation_error("de", {{"variant", 2.5}}) ==
        "options/variant: 2.5: expected an integer in [1, 10]");
  CHECK(validation_error("de", {{"F", 1.5}}) == "options/F: 1.5: expected a number in [0, 1]");
  CHECK(validation_error("cmaes", {{"sigma0", 0}}) ==
        "options/sigma0: 0: expected a number in (0, 1]");
  CHECK(validation_error("cmaes", {{"population", "20"}}) ==
        "options/population: \"20\": expected an integer in [1, 1000000]");
  for (const json& v : {json::array(), json({1, 1}), json({19}), json("2")}) {
    CHECK(validation_error("de1220", {{"allowed_variants", v}}) ==
          "options/allowed_variants: " + v.dump() +
              ": expected a non-empty array of distinct integers in [1, 18]");
  }
  CHECK(validation_error("cmaes", json::array()) == "options: []: expected an object");

  // Through the optimizer's own checks, and run_optimizer refuses to start.
  auto o = pagmo_options("cmaes", {{"population", 3}}, 100);
  CHECK_FALSE(o.validate(&error));
  CHECK(error.rfind("options/population: 3: expected a population of at least 5", 0) == 0);
  const auto r = run_optimizer(shifted_quadratic(2), o);
  CHECK(r.status == OptimizerStatus::kFailed);
  CHECK(r.evaluations == 0);
}
