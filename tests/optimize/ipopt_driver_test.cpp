// Ipopt driver: analytic problems, option pass-through, no ./ipopt.opt, stop
// flag, determinism across the Problem's thread count.
#include <catch2/catch.hpp>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "optimize/ipopt_driver.hpp"
#include "optimize/optimizer.hpp"
#include "tests/optimize/driver_test_problems.hpp"

using namespace pronk::optimize;
using namespace pronk::optimize::test;

namespace {

/// Runs `f` with the working directory set to a fresh temporary directory.
template <class F>
void in_temp_dir(const std::string& name, F&& f) {
  namespace fs = std::filesystem;
  const fs::path old = fs::current_path();
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::current_path(dir);
  try {
    f();
  } catch (...) {
    fs::current_path(old);
    fs::remove_all(dir);
    throw;
  }
  fs::current_path(old);
  fs::remove_all(dir);
}

}  // namespace

TEST_CASE("Ipopt solves the shifted quadratic and Rosenbrock", "[optimize][ipopt]") {
  for (const char* scheme : {"forward", "central"}) {
    INFO(scheme);
    auto o = ipopt_options();
    o.fd_scheme = scheme;
    const auto q = shifted_quadratic(3);
    Recorder rec;
    const auto r = run_optimizer(q, o, &rec);
    INFO(r.brief_report());
    CHECK(r.status == OptimizerStatus::kConverged);
    CHECK(r.library_status == "Solve_Succeeded");
    CHECK(distance(r.best_x, {1.0, -0.5, 0.25}) < 1e-5);
    CHECK(r.gradient_evaluations > 0);
    REQUIRE(static_cast<long>(rec.seen.size()) == r.evaluations);
    for (std::size_t i = 0; i < rec.seen.size(); ++i)
      REQUIRE(rec.seen[i].index == static_cast<long>(i));
  }
  // Rosenbrock needs accurate (central) differences to converge to 1e-5.
  const auto rb = rosenbrock();
  const auto r2 = run_optimizer(rb, ipopt_options());
  INFO(r2.brief_report());
  CHECK(r2.status == OptimizerStatus::kConverged);
  CHECK(distance(r2.best_x, {1.0, 1.0}) < 1e-5);
}

TEST_CASE("Ipopt solves the constrained problem", "[optimize][ipopt]") {
  const auto p = constrained_circle();
  Recorder rec;
  const auto r = run_optimizer(p, ipopt_options(), &rec);
  INFO(r.brief_report() << "\n" << r.full_report(p));
  CHECK(r.status == OptimizerStatus::kConverged);
  CHECK(r.best_feasible);
  CHECK_FALSE(r.constraints_as_penalty);
  CHECK(distance(r.best_x, {0.5, 0.5}) < 1e-5);
  CHECK(r.best_cost == Approx(0.5).margin(1e-5));
  CHECK(r.full_report(p).find("passed to the optimizer") != std::string::npos);
}

TEST_CASE("Ipopt options are passed through and checked", "[optimize][ipopt]") {
  const auto p = rosenbrock();
  SECTION("max_iter is respected") {
    auto o = ipopt_options();
    o.ipopt_options = {{"max_iter", 3}};
    const auto r = run_optimizer(p, o);
    CHECK(r.library_status == "Maximum_Iterations_Exceeded");
    CHECK(r.status == OptimizerStatus::kMaxEvaluations);
    CHECK(r.evaluations < 40);
    CHECK_FALSE(r.best_x.empty());
  }
  SECTION("numbers, integers given for numbers, and strings") {
    auto o = ipopt_options();
    o.ipopt_options = {{"tol", 1e-9}, {"acceptable_tol", 1}, {"mu_strategy", "adaptive"}};
    std::string error;
    CHECK(o.validate(&error));
    const auto r = run_optimizer(p, o);
    CHECK(r.status == OptimizerStatus::kConverged);
  }
  SECTION("an unknown option is rejected cleanly") {
    auto o = ipopt_options();
    o.ipopt_options = {{"max_itr", 3}};
    std::string error;
    CHECK_FALSE(o.validate(&error));
    CHECK(error == "ipopt_options/max_itr: 3: unknown Ipopt option");
    const auto r = run_optimizer(p, o);
    CHECK(r.status == OptimizerStatus::kFailed);
    CHECK(r.evaluations == 0);
    CHECK(r.message.find("max_itr") != std::string::npos);
  }
  SECTION("wrong types and rejected values") {
    std::string error;
    CHECK_FALSE(validate_ipopt_options({{"max_iter", "ten"}}, &error));
    CHECK(error.find("expected an integer") != std::string::npos);
    CHECK_FALSE(validate_ipopt_options({{"max_iter", 2.5}}, &error));
    CHECK_FALSE(validate_ipopt_options({{"tol", -1.0}}, &error));
    CHECK(error.find("rejected") != std::string::npos);
    CHECK_FALSE(validate_ipopt_options({{"mu_strategy", "fastest"}}, &error));
    CHECK_FALSE(validate_ipopt_options({{"hessian_approximation", "exact"}}, &error));
    CHECK_FALSE(validate_ipopt_options(nlohmann::json::array(), &error));
    CHECK(validate_ipopt_options(nlohmann::json::object(), &error));
  }
}

TEST_CASE("Ipopt does not read ./ipopt.opt", "[optimize][ipopt]") {
  in_temp_dir("pronk_ipopt_opt_test", [] {
    {
      std::ofstream f("ipopt.opt");
      f << "max_iter 1\nlinear_solver ma27\n";
    }
    const auto p = rosenbrock();
    const auto r = run_optimizer(p, ipopt_options());
    INFO(r.brief_report());
    CHECK(r.status == OptimizerStatus::kConverged);
    CHECK(distance(r.best_x, {1.0, 1.0}) < 1e-5);
  });
}

TEST_CASE("Ipopt stop flag and evaluation budget", "[optimize][ipopt]") {
  const auto p = rosenbrock();
  SECTION("stop flag") {
    std::atomic<bool> flag{false};
    auto o = ipopt_options();
    o.stop_flag = &flag;
    Recorder rec;
    rec.flag = &flag;
    rec.stop_after = 20;
    const auto r = run_optimizer(p, o, &rec);
    INFO(r.brief_report());
    CHECK(r.status == OptimizerStatus::kStopped);
    CHECK(r.evaluations >= 20);
    CHECK(r.evaluations <= 20 + 3);
    CHECK_FALSE(r.best_x.empty());
    CHECK(r.best_index >= 0);
  }
  SECTION("budget") {
    auto o = ipopt_options();
    o.max_evaluations = 30;
    const auto r = run_optimizer(p, o);
    INFO(r.brief_report());
    CHECK(r.status == OptimizerStatus::kMaxEvaluations);
    CHECK(r.evaluations <= 30);
    CHECK(r.message.find("budget") != std::string::npos);
  }
}

TEST_CASE("Ipopt results do not depend on the Problem's thread count", "[optimize][ipopt]") {
  auto p1 = constrained_circle();
  auto p2 = constrained_circle();
  p2.threads = 2;
  Recorder a, b;
  const auto ra = run_optimizer(p1, ipopt_options(), &a);
  const auto rb = run_optimizer(p2, ipopt_options(), &b);
  REQUIRE(a.seen.size() == b.seen.size());
  for (std::size_t i = 0; i < a.seen.size(); ++i) {
    REQUIRE(a.seen[i].x == b.seen[i].x);
    REQUIRE(a.seen[i].e.cost == b.seen[i].e.cost);
  }
  CHECK(ra.best_x == rb.best_x);
  CHECK(ra.evaluations == rb.evaluations);
}
