// Fault injection for every exposed algorithm: failed evaluations, a fake
// attractive optimum inside a failing region, NaN/inf values and throwing
// Problems never lead to a result converged at a wrong point, and best_x never
// comes from a failed evaluation.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/optimizer.hpp"
#include "tests/optimize/driver_test_problems.hpp"

using namespace pronk::optimize;
using namespace pronk::optimize::test;

namespace {

struct Case {
  const char* name;
  const char* local;
  long budget;
  double tolerance;
};

const std::vector<Case> kCases = {
    {"LN_BOBYQA", "", 400, 1e-4},
    {"LN_COBYLA", "", 600, 1e-3},
    {"LN_NELDERMEAD", "", 600, 1e-3},
    {"LN_SBPLX", "", 600, 1e-3},
    {"GN_CRS2_LM", "", 2000, 1e-2},
    {"GN_ISRES", "", 4000, 5e-2},
    {"GN_DIRECT_L", "", 2000, 1e-2},
    {"GD_STOGO", "", 2000, 1e-2},
    {"G_MLSL_LDS", "LN_BOBYQA", 1500, 1e-3},
    {"AUGLAG", "LN_BOBYQA", 800, 1e-3},
    {"LD_LBFGS", "", 600, 1e-3},
    {"LD_SLSQP", "", 600, 1e-3},
    {"LD_MMA", "", 600, 1e-2},
    {"ipopt", "", 2000, 1e-4},
};

OptimizerOptions options_for(const Case& c) {
  OptimizerOptions o =
      std::string(c.name) == "ipopt" ? ipopt_options() : nlopt_options(c.name, c.budget);
  if (*c.local) o.local_algorithm = c.local;
  o.max_evaluations = c.budget;
  return o;
}

/// The fake optimum: a disc of radius 0.6 around (-2, 2) where every
/// evaluation fails but reports a very attractive "penalty" (or NaN).
bool in_fake_region(const std::vector<double>& x) {
  return std::hypot(x[0] + 2.0, x[1] - 2.0) < 0.6;
}

/// The shifted quadratic plus a deep fake well at (-2, 2), as if a broken
/// model produced it; evaluations there fail.
LambdaProblem fake_optimum_problem(bool nan) {
  return LambdaProblem(
      {-3.0, -3.0}, {3.0, 3.0}, {-1.0, 1.0}, 0, [nan](const std::vector<double>& x) {
        ProblemEvaluation e = quadratic_at(x);
        if (in_fake_region(x)) {
          if (nan) {
            e.cost =
                std::numeric_limits<double>::quiet_NaN();  // a contract breach: must be clamped
          } else {
            e.ok = false;
            e.failure = "simulated fall";
            e.cost = -100.0 + std::hypot(x[0] + 2.0, x[1] - 2.0);
          }
        }
        return e;
      });
}

/// Checks the fault-injection contract on one result.
void check_contract(const Recorder& rec, const OptimizerResult& r, double tolerance) {
  REQUIRE(static_cast<long>(rec.seen.size()) == r.evaluations);
  for (std::size_t i = 0; i < rec.seen.size(); ++i) {
    REQUIRE(rec.seen[i].index == static_cast<long>(i));
    REQUIRE(std::isfinite(rec.seen[i].e.cost));  // observers never see NaN either
  }
  REQUIRE(r.best_index >= 0);
  const Observed& best = rec.seen[static_cast<std::size_t>(r.best_index)];
  CHECK(best.e.ok);  // best_x never comes from a failed evaluation
  CHECK(best.x == r.best_x);
  CHECK(std::isfinite(r.best_cost));
  if (r.status == OptimizerStatus::kConverged) CHECK(distance(r.best_x, kCentre) < tolerance);
}

}  // namespace

TEST_CASE("Fault injection: a failing region with a fake optimum", "[optimize][faults]") {
  for (const bool nan : {false, true}) {
    const auto p = fake_optimum_problem(nan);
    for (const auto& c : kCases) {
      INFO(c.name << (nan ? " (NaN)" : " (failed)"));
      Recorder rec;
      const auto r = run_optimizer(p, options_for(c), &rec);
      INFO(r.brief_report());
      check_contract(rec, r, c.tolerance);
      CHECK_FALSE(in_fake_region(r.best_x));
      if (nan) CHECK(r.nonfinite_evaluations == r.failed_evaluations);
    }
  }
}

TEST_CASE("Fault injection: every 7th evaluation fails", "[optimize][faults]") {
  for (const auto& c : kCases) {
    INFO(c.name);
    auto counter = std::make_shared<std::atomic<long>>(0);
    LambdaProblem p({-3.0, -3.0}, {3.0, 3.0}, {-2.0, -2.0}, 0,
                    [counter](const std::vector<double>& x) {
                      ProblemEvaluation e = quadratic_at(x);
                      const long k = ++*counter;
                      if (k % 7 == 0) {
                        e.ok = false;
                        e.failure = "injected failure";
                        e.cost = (k % 2 == 0) ? -1e3 : 1e3;  // sometimes a misleading penalty
                      } else if (k % 11 == 0) {
                        e.cost = std::numeric_limits<double>::infinity();  // must be clamped
                      }
                      return e;
                    });
    Recorder rec;
    const auto r = run_optimizer(p, options_for(c), &rec);
    INFO(r.brief_report());
    check_contract(rec, r, c.tolerance);
    CHECK(r.failed_evaluations > 0);
    if (r.evaluations >= 11) CHECK(r.nonfinite_evaluations > 0);
  }
}

TEST_CASE("Fault injection: constrained problem with failures", "[optimize][faults]") {
  for (const char* name : {"LN_COBYLA", "GN_ISRES", "LD_SLSQP", "ipopt"}) {
    INFO(name);
    LambdaProblem p({-2.0, -2.0}, {2.0, 2.0}, {1.5, 1.5}, 1, [](const std::vector<double>& x) {
      ProblemEvaluation e;
      e.cost = x[0] * x[0] + x[1] * x[1];
      e.constraints = {1.0 - x[0] - x[1]};
      if (x[0] < 0.2 && x[1] < 0.2) {  // infeasible and failing corner with a fake minimum
        e.ok = false;
        e.cost = -10.0;
        e.constraints = {std::numeric_limits<double>::quiet_NaN()};
      }
      return e;
    });
    Case c{name, "", std::string(name) == "GN_ISRES" ? 6000 : 800, 3e-2};
    Recorder rec;
    const auto r = run_optimizer(p, options_for(c), &rec);
    INFO(r.brief_report());
    REQUIRE(r.best_index >= 0);
    CHECK(rec.seen[static_cast<std::size_t>(r.best_index)].e.ok);
    if (r.status == OptimizerStatus::kConverged)
      CHECK(distance(r.best_x, {0.5, 0.5}) < c.tolerance);
  }
}

TEST_CASE("A Problem that throws ends the run as failed with the cause", "[optimize][faults]") {
  for (const auto& c : kCases) {
    INFO(c.name);
    auto counter = std::make_shared<std::atomic<long>>(0);
    LambdaProblem p({-3.0, -3.0}, {3.0, 3.0}, {-2.0, -2.0}, 0,
                    [counter](const std::vector<double>& x) {
                      if (++*counter == 10)
                        throw std::runtime_error("scene pointer /controller/kp/9 missing");
                      return quadratic_at(x);
                    });
    Recorder rec;
    const auto r = run_optimizer(p, options_for(c), &rec);
    INFO(r.brief_report());
    CHECK(r.status == OptimizerStatus::kFailed);
    CHECK(r.message.find("scene pointer /controller/kp/9 missing") != std::string::npos);
    CHECK(r.evaluations < 10);
    CHECK(static_cast<long>(rec.seen.size()) == r.evaluations);
    CHECK_FALSE(r.best_x.empty());
  }
  SECTION("an observer that throws also stops the run cleanly") {
    struct Throwing : EvaluationObserver {
      void on_evaluation(long index, const std::vector<double>&, const ProblemEvaluation&,
                         const char*) override {
        if (index == 5) throw std::runtime_error("journal: disk full");
      }
    } obs;
    const auto p = shifted_quadratic();
    for (const char* lib : {"nlopt", "ipopt"}) {
      auto o = std::string(lib) == "ipopt" ? ipopt_options() : nlopt_options("LN_BOBYQA", 100);
      const auto r = run_optimizer(p, o, &obs);
      CHECK(r.status == OptimizerStatus::kFailed);
      CHECK(r.message.find("journal: disk full") != std::string::npos);
    }
  }
}

TEST_CASE("A failed starting point is survivable", "[optimize][faults]") {
  for (const auto& c : kCases) {
    INFO(c.name);
    // Everything with x0 < -1.5 fails (including the start).
    LambdaProblem p({-3.0, -3.0}, {3.0, 3.0}, {-2.0, -2.0}, 0, [](const std::vector<double>& x) {
      ProblemEvaluation e = quadratic_at(x);
      if (x[0] < -1.5) {
        e.ok = false;
        e.cost = 1e3;
      }
      return e;
    });
    Recorder rec;
    const auto r = run_optimizer(p, options_for(c), &rec);
    INFO(r.brief_report());
    CHECK(static_cast<long>(rec.seen.size()) == r.evaluations);
    if (r.best_index >= 0) {
      CHECK(rec.seen[static_cast<std::size_t>(r.best_index)].e.ok);
      CHECK(r.best_x[0] >= -1.5);
    } else {
      CHECK(r.status != OptimizerStatus::kConverged);
      CHECK(r.best_x.empty());
    }
    if (r.status == OptimizerStatus::kConverged) CHECK(distance(r.best_x, kCentre) < c.tolerance);
  }
}
