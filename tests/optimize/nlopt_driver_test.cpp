// NLopt driver: every exposed algorithm on analytic problems with known minima,
// constraints (native and penalty), seeding, stop flag, observer contract.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstring>
#include <string>
#include <vector>

#include "optimize/nlopt_driver.hpp"
#include "optimize/optimizer.hpp"
#include "tests/optimize/driver_test_problems.hpp"

using namespace pronk::optimize;
using namespace pronk::optimize::test;

namespace {

struct AlgorithmCase {
  const char* name;
  const char* local;
  long budget;
  double tolerance;  ///< on |x - x*|
};

/// The algorithms the driver exposes and tests (any other NLopt name works too).
const std::vector<AlgorithmCase> kAlgorithms = {
    {"LN_BOBYQA", "", 400, 1e-5},
    {"LN_COBYLA", "", 600, 1e-4},
    {"LN_NELDERMEAD", "", 600, 1e-4},
    {"LN_SBPLX", "", 600, 1e-4},
    {"LN_NEWUOA_BOUND", "", 400, 1e-4},
    {"LN_PRAXIS", "", 600, 1e-4},
    {"GN_CRS2_LM", "", 3000, 1e-3},
    {"GN_ISRES", "", 6000, 3e-2},
    {"GN_DIRECT_L", "", 3000, 1e-3},
    {"GN_ESCH", "", 6000, 1e-1},
    {"GD_STOGO", "", 3000, 1e-3},
    {"G_MLSL_LDS", "LN_BOBYQA", 1500, 1e-4},
    {"G_MLSL", "LN_SBPLX", 1500, 1e-3},
    {"AUGLAG", "LN_BOBYQA", 800, 1e-4},
    {"LD_LBFGS", "", 400, 1e-4},
    {"LD_SLSQP", "", 400, 1e-4},
    {"LD_MMA", "", 600, 1e-3},
    {"LD_CCSAQ", "", 600, 1e-3},
    {"LD_TNEWTON_PRECOND_RESTART", "", 400, 1e-4},
};

/// Checks the observer contract against a result.
void check_observed(const Recorder& rec, const OptimizerResult& r) {
  REQUIRE(static_cast<long>(rec.seen.size()) == r.evaluations);
  long gradient = 0, failed = 0;
  for (std::size_t i = 0; i < rec.seen.size(); ++i) {
    REQUIRE(rec.seen[i].index == static_cast<long>(i));
    if (rec.seen[i].purpose == "gradient") ++gradient;
    if (!rec.seen[i].e.ok) ++failed;
  }
  CHECK(gradient == r.gradient_evaluations);
  CHECK(failed == r.failed_evaluations);
  if (r.best_index >= 0) {
    const Observed& b = rec.seen[static_cast<std::size_t>(r.best_index)];
    CHECK(b.e.ok);
    CHECK(b.x == r.best_x);
    CHECK(b.e.cost == r.best_cost);
  }
}

}  // namespace

TEST_CASE("NLopt algorithm names are NLopt's own", "[optimize][nlopt]") {
  CHECK(is_nlopt_algorithm("LN_BOBYQA"));
  CHECK(is_nlopt_algorithm("GD_STOGO"));
  CHECK(is_nlopt_algorithm("G_MLSL_LDS"));
  CHECK_FALSE(is_nlopt_algorithm("LN_BOBYQ"));
  CHECK_FALSE(is_nlopt_algorithm(""));
  CHECK(nlopt_supports_inequality_constraints("LN_COBYLA"));
  CHECK(nlopt_supports_inequality_constraints("GN_ISRES"));
  CHECK(nlopt_supports_inequality_constraints("AUGLAG"));
  CHECK(nlopt_supports_inequality_constraints("LD_SLSQP"));
  CHECK_FALSE(nlopt_supports_inequality_constraints("LN_BOBYQA"));
  CHECK_FALSE(nlopt_supports_inequality_constraints("G_MLSL_LDS"));

  OptimizerOptions o;
  std::string error;
  CHECK(o.validate(&error));
  o.algorithm = "LN_BOBYQ";
  CHECK_FALSE(o.validate(&error));
  CHECK(error.rfind("algorithm: LN_BOBYQ:", 0) == 0);
  o.algorithm = "G_MLSL_LDS";
  o.local_algorithm = "GN_DIRECT";
  CHECK_FALSE(o.validate(&error));
  CHECK(error.rfind("local_algorithm: GN_DIRECT:", 0) == 0);
  o = OptimizerOptions{};
  o.max_evaluations = 0;
  CHECK_FALSE(o.validate(&error));
  o = OptimizerOptions{};
  o.fd_scheme = "backward";
  CHECK_FALSE(o.validate(&error));
  o = OptimizerOptions{};
  o.library = "ceres";
  CHECK_FALSE(o.validate(&error));
  CHECK(error == "library: ceres: expected \"nlopt\", \"ipopt\" or \"pagmo\"");

  const auto p = shifted_quadratic();
  o = nlopt_options("NOT_AN_ALGORITHM", 10);
  const auto r = run_optimizer(p, o);
  CHECK(r.status == OptimizerStatus::kFailed);
  CHECK(r.evaluations == 0);
  CHECK(r.message.find("NOT_AN_ALGORITHM") != std::string::npos);
}

TEST_CASE("Every exposed NLopt algorithm finds the shifted quadratic minimum",
          "[optimize][nlopt]") {
  const auto p = shifted_quadratic(2);
  for (const auto& a : kAlgorithms) {
    INFO(a.name);
    auto o = nlopt_options(a.name, a.budget);
    if (*a.local) o.local_algorithm = a.local;
    Recorder rec;
    const auto r = run_optimizer(p, o, &rec);
    INFO(r.brief_report());
    CHECK(r.status != OptimizerStatus::kFailed);
    CHECK(r.evaluations <= a.budget);
    CHECK(r.evaluations > 0);
    CHECK(distance(r.best_x, kCentre) < a.tolerance);
    CHECK(r.best_feasible);
    CHECK(r.failed_evaluations == 0);
    check_observed(rec, r);
    const bool derivative = std::string(a.name).substr(1, 1) == "D";
    CHECK((r.gradient_evaluations > 0) == derivative);
  }
}

TEST_CASE("Local NLopt algorithms solve the bounded Rosenbrock problem", "[optimize][nlopt]") {
  const auto p = rosenbrock();
  const std::vector<AlgorithmCase> cases = {{"LN_BOBYQA", "", 1500, 1e-3},
                                            {"LN_SBPLX", "", 4000, 1e-3},
                                            {"LN_NELDERMEAD", "", 4000, 1e-3},
                                            {"LD_LBFGS", "", 3000, 1e-3},
                                            {"LD_SLSQP", "", 3000, 1e-3}};
  for (const auto& a : cases) {
    INFO(a.name);
    auto o = nlopt_options(a.name, a.budget);
    o.xtol_rel = 1e-10;
    o.fd_scheme = "central";
    const auto r = run_optimizer(p, o);
    INFO(r.brief_report());
    CHECK(distance(r.best_x, {1.0, 1.0}) < a.tolerance);
  }
}

TEST_CASE("NLopt constrained problem: native constraints and the penalty", "[optimize][nlopt]") {
  const auto p = constrained_circle();
  const std::vector<AlgorithmCase> native = {{"LN_COBYLA", "", 800, 1e-4},
                                             {"GN_ISRES", "", 8000, 3e-2},
                                             {"AUGLAG", "LN_BOBYQA", 3000, 1e-3},
                                             {"LD_SLSQP", "", 600, 1e-4},
                                             {"LD_MMA", "", 1500, 1e-3}};
  for (const auto& a : native) {
    INFO(a.name);
    auto o = nlopt_options(a.name, a.budget);
    if (*a.local) o.local_algorithm = a.local;
    Recorder rec;
    const auto r = run_optimizer(p, o, &rec);
    INFO(r.brief_report() << "\n" << r.full_report(p));
    CHECK_FALSE(r.constraints_as_penalty);
    CHECK(r.best_feasible);
    CHECK(r.best_constraints.size() == 1);
    CHECK(distance(r.best_x, {0.5, 0.5}) < a.tolerance);
    check_observed(rec, r);
  }

  SECTION("BOBYQA and MLSL get a quadratic penalty and say so") {
    for (const char* name : {"LN_BOBYQA", "G_MLSL_LDS"}) {
      INFO(name);
      auto o = nlopt_options(name, 1500);
      o.penalty_weight = 1e6;
      const auto r = run_optimizer(p, o);
      INFO(r.brief_report());
      CHECK(r.constraints_as_penalty);
      CHECK(r.message.find("quadratic penalty") != std::string::npos);
      CHECK(r.best_feasible);
      CHECK(distance(r.best_x, {0.5, 0.5}) < 1e-2);
      CHECK(r.full_report(p).find("quadratic penalty in the cost") != std::string::npos);
    }
  }
}

TEST_CASE("Seeded NLopt runs of random algorithms are identical", "[optimize][nlopt]") {
  const auto p = shifted_quadratic(3);
  for (const char* name : {"GN_ISRES", "GN_CRS2_LM", "G_MLSL"}) {
    INFO(name);
    auto o = nlopt_options(name, 300);
    o.seed = 42;
    Recorder a, b, c;
    const auto ra = run_optimizer(p, o, &a);
    const auto rb = run_optimizer(p, o, &b);
    REQUIRE(a.seen.size() == b.seen.size());
    for (std::size_t i = 0; i < a.seen.size(); ++i) REQUIRE(a.seen[i].x == b.seen[i].x);
    CHECK(ra.best_x == rb.best_x);
    CHECK(ra.best_index == rb.best_index);
    o.seed = 43;
    run_optimizer(p, o, &c);
    bool differs = c.seen.size() != a.seen.size();
    for (std::size_t i = 0; !differs && i < a.seen.size(); ++i)
      differs = a.seen[i].x != c.seen[i].x;
    CHECK(differs);
  }
}

TEST_CASE("NLopt results do not depend on the Problem's thread count", "[optimize][nlopt]") {
  for (const char* name : {"LD_LBFGS", "GN_ISRES", "LN_COBYLA"}) {
    INFO(name);
    auto p1 = constrained_circle();
    auto p3 = constrained_circle();
    p3.threads = 3;
    auto o = nlopt_options(name, 300);
    o.fd_scheme = "central";
    Recorder a, b;
    const auto ra = run_optimizer(p1, o, &a);
    const auto rb = run_optimizer(p3, o, &b);
    REQUIRE(a.seen.size() == b.seen.size());
    for (std::size_t i = 0; i < a.seen.size(); ++i) {
      REQUIRE(a.seen[i].x == b.seen[i].x);
      REQUIRE(a.seen[i].purpose == b.seen[i].purpose);
    }
    CHECK(ra.best_x == rb.best_x);
    CHECK(ra.status == rb.status);
  }
}

TEST_CASE("NLopt stop flag and limits", "[optimize][nlopt]") {
  const auto p = shifted_quadratic(2);
  SECTION("stop flag set after N evaluations") {
    for (const char* name : {"LN_BOBYQA", "GN_DIRECT_L", "LD_LBFGS", "G_MLSL_LDS"}) {
      INFO(name);
      std::atomic<bool> flag{false};
      auto o = nlopt_options(name, 1000);
      o.stop_flag = &flag;
      Recorder rec;
      rec.flag = &flag;
      rec.stop_after = 17;
      const auto r = run_optimizer(p, o, &rec);
      INFO(r.brief_report());
      CHECK(r.status == OptimizerStatus::kStopped);
      CHECK(r.evaluations >= 17);
      CHECK(r.evaluations <= 17 + 2 * 2 + 1);  // at most the rest of one stencil
      CHECK_FALSE(r.best_x.empty());
      check_observed(rec, r);
    }
  }
  SECTION("evaluation budget, including finite-difference points") {
    for (const char* name : {"LN_SBPLX", "LD_SLSQP", "GD_STOGO"}) {
      INFO(name);
      auto o = nlopt_options(name, 25);
      o.xtol_rel = 0.0;
      const auto p3 = shifted_quadratic(3);
      const auto r = run_optimizer(p3, o);
      INFO(r.brief_report());
      CHECK(r.evaluations <= 25);
      if (r.status != OptimizerStatus::kConverged)
        CHECK(r.status == OptimizerStatus::kMaxEvaluations);
    }
  }
  SECTION("a stop flag set before the run evaluates nothing") {
    std::atomic<bool> flag{true};
    auto o = nlopt_options("LN_BOBYQA", 100);
    o.stop_flag = &flag;
    const auto r = run_optimizer(p, o);
    CHECK(r.status == OptimizerStatus::kStopped);
    CHECK(r.evaluations == 0);
    CHECK(r.best_index == -1);
  }
}

TEST_CASE("NLopt gradient algorithms stalled by forward differences say why", "[optimize][nlopt]") {
  const auto p = shifted_quadratic(2);
  auto o = nlopt_options("LD_LBFGS", 400);
  o.fd_scheme = "forward";
  const auto r = run_optimizer(p, o);
  INFO(r.brief_report());
  if (r.status == OptimizerStatus::kFailed) {
    CHECK(r.library_status == "FAILURE");
    CHECK(r.message.find("finite-difference gradient noise") != std::string::npos);
  }
  CHECK(distance(r.best_x, kCentre) < 1e-4);  // the best point is still returned
}

TEST_CASE("NLopt result reports", "[optimize][nlopt]") {
  const auto p = constrained_circle();
  const auto r = run_optimizer(p, nlopt_options("LN_COBYLA", 500));
  const std::string brief = r.brief_report();
  CHECK(brief.find('\n') == std::string::npos);
  CHECK(brief.find("nlopt LN_COBYLA: converged") == 0);
  const std::string full = r.full_report(p);
  CHECK(full.find("p0") != std::string::npos);
  CHECK(full.find("p1") != std::string::npos);
  CHECK(full.find("c0") != std::string::npos);
  CHECK(full.find("active") != std::string::npos);
  CHECK(full.find("evaluations") != std::string::npos);
  CHECK(r.wall_time >= r.evaluation_time);
  CHECK(r.evaluation_time >= 0.0);
}
