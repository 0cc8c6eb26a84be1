// SolverOptions::validate() and the method names.
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "sim/ode/solver.hpp"

using pronk::ode::Method;
using pronk::ode::SolverOptions;

TEST_CASE("ode: method names round-trip", "[ode]") {
  for (Method m : {Method::kEuler, Method::kRk2, Method::kRk4, Method::kDopri5, Method::kRodas4,
                   Method::kRadau5}) {
    Method parsed = Method::kEuler;
    REQUIRE(pronk::ode::parse_method(pronk::ode::to_string(m), &parsed));
    CHECK(parsed == m);
    CHECK(pronk::ode::is_adaptive(m) ==
          (m == Method::kDopri5 || m == Method::kRodas4 || m == Method::kRadau5));
  }
  Method out = Method::kRk4;
  CHECK_FALSE(pronk::ode::parse_method("rk45", &out));
  CHECK(out == Method::kRk4);
}

TEST_CASE("ode: validate accepts the defaults and rejects each bad field", "[ode]") {
  std::string error = "stale";
  CHECK(SolverOptions{}.validate(&error));
  CHECK(error.empty());

  struct Bad {
    const char* field;
    void (*apply)(SolverOptions&);
  };
  const Bad bad[] = {
      {"rtol", [](SolverOptions& o) { o.rtol = -1; }},
      {"rtol", [](SolverOptions& o) { o.rtol = 0; }},
      {"rtol", [](SolverOptions& o) { o.rtol = std::numeric_limits<double>::infinity(); }},
      {"atol", [](SolverOptions& o) { o.atol = std::numeric_limits<double>::quiet_NaN(); }},
      {"atol", [](SolverOptions& o) { o.atol = -1e-9; }},
      {"h_fixed", [](SolverOptions& o) { o.h_fixed = 0; }},
      {"h_max", [](SolverOptions& o) { o.h_max = 0; }},
      {"h_min", [](SolverOptions& o) { o.h_min = -1; }},
      {"h_min", [](SolverOptions& o) { o.h_min = 1.0; }},  // >= h_max
      {"h_initial", [](SolverOptions& o) { o.h_initial = -0.1; }},
      {"event_tol", [](SolverOptions& o) { o.event_tol = 0; }},
      {"max_steps", [](SolverOptions& o) { o.max_steps = 0; }},
  };
  for (const Bad& b : bad) {
    SolverOptions o;
    b.apply(o);
    error.clear();
    INFO(b.field);
    CHECK_FALSE(o.validate(&error));
    CHECK(error.rfind(std::string(b.field) + ": ", 0) == 0);
  }
  SolverOptions o;
  o.rtol = -1;
  CHECK_FALSE(o.validate(&error));
  CHECK(error == "rtol: -1: must be > 0");
  o = SolverOptions{};
  o.h_min = 0.5;
  CHECK_FALSE(o.validate(&error));
  CHECK(error == "h_min: 0.5: must be < h_max");
  CHECK_FALSE(o.validate(nullptr));
}
