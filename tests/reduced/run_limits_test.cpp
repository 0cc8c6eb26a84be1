// Tests of sim/reduced/run_limits.hpp: the records a robot run holds (trajectory samples
// = duration / sample_interval, strides) are bounded by 1e7 each, and a fixed step longer
// than half the shortest flight is refused, in every model and at every entry: the scene
// loader (io::InputError naming the pointer, with the numbers), reduced::simulate and
// robot::simulate (std::invalid_argument for memory, `diverged` at t = 0 for the step).
#include "sim/reduced/run_limits.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "io/load/input_error.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "tests/extremes/extremes_support.hpp"
#include "tests/support/scenes.hpp"

using namespace pronk;
using Catch::Matchers::Contains;
namespace ex = pronk::test::extremes;

namespace {

/// The io::InputError that loading the shipped scene `name` with `set` throws.
io::InputError load_error(const std::string& name, const std::vector<std::string>& set) {
  try {
    test::load_shipped(name, set);
  } catch (const io::InputError& e) {
    return e;
  }
  FAIL("the scene loaded; expected an io::InputError");
  throw std::logic_error("unreachable");
}

/// The rise time to the apex of a hop of height h [m] at gravity g [m/s^2]: sqrt(2 h / g).
double rise_time(double h, double g) { return std::sqrt(2.0 * h / g); }

}  // namespace

TEST_CASE("run limits: at most 1e7 trajectory samples (duration / sample_interval) and strides",
          "[run_limits]") {
  scene::Simulation sim;
  sim.duration = 1e6;  // the issue's run: 9.6 GB after 35 s
  sim.sample_interval = 0.005;
  CHECK(reduced::trajectory_samples(sim) == Approx(2e8));
  auto b = reduced::memory_limit_breach(sim, true, true);
  REQUIRE(b);
  CHECK(b->field == "sample_interval");
  CHECK(b->found == "2e+08 samples (duration 1e+06 s / sample_interval 0.005 s)");
  CHECK(b->expected ==
        "at most 1e+07 trajectory samples held in memory (duration / sample_interval)");
  CHECK_FALSE(reduced::memory_limit_breach(sim, false, true));  // nothing recorded: no limit

  sim.duration = 10.0;
  sim.sample_interval = 1e-9;  // the issue's other run: 9.1 GB after 25 s
  b = reduced::memory_limit_breach(sim, true, true);
  REQUIRE(b);
  CHECK(b->found == "1e+10 samples (duration 10 s / sample_interval 1e-09 s)");

  sim.sample_interval = 0.0625;  // exact in binary: exactly 1e7 samples pass
  sim.duration = 625000.0;
  CHECK(reduced::trajectory_samples(sim) == 1e7);
  CHECK_FALSE(reduced::memory_limit_breach(sim, true, true));
  sim.duration = std::nextafter(625000.0, 1e9);
  CHECK(reduced::memory_limit_breach(sim, true, true));

  sim.duration = 10.0;
  sim.max_strides = reduced::kMaxStrides;
  CHECK_FALSE(reduced::memory_limit_breach(sim, true, true));
  sim.max_strides = reduced::kMaxStrides + 1;
  b = reduced::memory_limit_breach(sim, true, true);
  REQUIRE(b);
  CHECK(b->field == "max_strides");
  CHECK(b->found == "max_strides 1e+07");  // 6 digits: 10000001 prints as 1e+07
  CHECK_FALSE(reduced::memory_limit_breach(sim, true, false));
}

TEST_CASE("run limits: the loader refuses a robot scene that would hold too many records",
          "[run_limits]") {
  for (const char* name : {"case1_body_only", "pr_running"}) {
    INFO(name);
    io::InputError e = load_error(name, {"/simulation/duration=1e6"});
    CHECK(e.pointer() == "/simulation/sample_interval");
    CHECK(e.found() == "2e+08 samples (duration 1e+06 s / sample_interval 0.005 s)");
    e = load_error(name, {"/simulation/sample_interval=1e-9"});
    CHECK(e.pointer() == "/simulation/sample_interval");
    CHECK_THAT(e.found(), Contains("1e+10 samples"));
    e = load_error(name, {"/simulation/max_strides=20000000"});
    CHECK(e.pointer() == "/simulation/max_strides");
    CHECK(e.found() == "max_strides 2e+07");
    CHECK(e.expected() == "at most 1e+07 stride records held in memory");
  }
  // A long duration with samples far enough apart is fine.
  const scene::Scene s = test::load_shipped(
      "case1_body_only", {"/simulation/duration=1e6", "/simulation/sample_interval=0.1"});
  CHECK(reduced::trajectory_samples(s.simulation) == Approx(1e7));
}

TEST_CASE("run limits: both simulators refuse a scene made in code that would hold too much",
          "[run_limits]") {
  scene::Scene s = test::load_shipped("case1_body_only");
  s.simulation.duration = 1e6;
  CHECK_THROWS_WITH(reduced::simulate(s),
                    "simulation.sample_interval: 2e+08 samples (duration 1e+06 s / "
                    "sample_interval 0.005 s): expected at most 1e+07 trajectory samples held in "
                    "memory (duration / sample_interval)");
  // Without the trajectory the same scene runs (here to its 3rd stride).
  s.simulation.max_strides = 3;
  reduced::RunOptions quiet;
  quiet.record_trajectory = false;
  const reduced::RunResult r = reduced::simulate(s, quiet);
  CHECK(r.status == reduced::RunStatus::kCompleted);
  CHECK(r.strides.size() == 3);
  // Strides are held unless the caller drops them.
  s.simulation.max_strides = reduced::kMaxStrides + 1;
  CHECK_THROWS_WITH(reduced::simulate(s, quiet), Contains("simulation.max_strides"));
  quiet.record_strides = false;
  s.simulation.duration = 1.0;
  CHECK(reduced::simulate(s, quiet).status == reduced::RunStatus::kCompleted);

  // The full model always holds its strides; it refuses before building the robot.
  scene::Scene f = test::load_shipped("pr_running");
  f.simulation.max_strides = reduced::kMaxStrides + 1;
  robot::RobotRunOptions no_samples;
  no_samples.record_trajectory = false;
  CHECK_THROWS_WITH(robot::simulate(f, no_samples), Contains("simulation.max_strides"));
  f.simulation.max_strides = 10;
  f.simulation.sample_interval = 1e-9;
  CHECK_THROWS_WITH(robot::simulate(f), Contains("1e+10 samples"));
}

TEST_CASE("run limits: the longest fixed step is the rise time to the lowest apex",
          "[run_limits]") {
  scene::Scene s = test::load_shipped("case1_body_only");  // hop height 0.2 m, g 9.81
  CHECK(reduced::max_fixed_step(s) == Approx(rise_time(0.2, 9.81)).epsilon(1e-15));
  s.controller.hop_height_changes = {{2.0, 0.35}, {4.0, 0.05}, {6.0, 0.3}};
  CHECK(reduced::max_fixed_step(s) == Approx(rise_time(0.05, 9.81)).epsilon(1e-15));
  s.gravity = 3.71;
  CHECK(reduced::max_fixed_step(s) == Approx(rise_time(0.05, 3.71)).epsilon(1e-15));
  s.gravity = 0.0;  // no flight ends: nothing to skip
  CHECK(reduced::max_fixed_step(s) == std::numeric_limits<double>::infinity());
  // Adaptive methods pass whatever h_fixed says.
  s.gravity = 9.81;
  ode::SolverOptions o;
  o.method = ode::Method::kDopri5;
  o.h_fixed = 10.0;
  CHECK_FALSE(reduced::fixed_step_breach(s, o));
  for (ode::Method m :
       {ode::Method::kEuler, ode::Method::kRk2, ode::Method::kRk4, ode::Method::kVerlet}) {
    o.method = m;
    CHECK(reduced::fixed_step_breach(s, o));
  }
}

TEST_CASE("run limits: Euler at h_fixed = 10 s is refused, not a completed run without touchdowns",
          "[run_limits][extremes]") {
  // The issue's run: `completed`, exit 0, z frozen at its start while vz = -29.4 m/s.
  const std::string expected =
      "a fixed step of at most 0.201928 s, half the 0.403855 s flight of the lowest hop height "
      "0.2 m at gravity 9.81 m/s^2 (a longer step can pass over a whole flight and miss its "
      "touchdown)";
  const io::InputError e = load_error(
      "case1_body_only", {"/simulation/solver/method=\"euler\"", "/simulation/solver/h_fixed=10"});
  CHECK(e.pointer() == "/simulation/solver/h_fixed");
  CHECK(e.found() == "h_fixed 10 s (euler)");
  CHECK(e.expected() == expected);
  // Made in code (a study's bound hop height, a map's model): diverged at t = 0.
  scene::Scene s = test::load_shipped("case1_body_only");
  s.simulation.solver.method = ode::Method::kEuler;
  s.simulation.solver.h_fixed = 10.0;
  const reduced::RunResult r = reduced::simulate(s);
  CHECK(r.status == reduced::RunStatus::kDiverged);
  CHECK(r.reason == "h_fixed 10 s (euler): expected " + expected);
  CHECK(r.t_end == 0.0);
  CHECK(r.trajectory.size() == 1);  // the initial sample
  CHECK(r.strides.empty());
  CHECK(ex::all_finite(r));
  // The full model's own solver, the same rule.
  const io::InputError ef =
      load_error("pr_running", {R"(/pseudo_rigid/solver={"method": "euler", "h_fixed": 10})"});
  CHECK(ef.pointer() == "/pseudo_rigid/solver/h_fixed");
  CHECK(ef.found() == "h_fixed 10 s (euler)");
  scene::Scene f = test::load_shipped("pr_running");
  f.pseudo_rigid.solver_auto = false;
  f.pseudo_rigid.solver.method = ode::Method::kVerlet;
  f.pseudo_rigid.solver.h_fixed = 10.0;
  const robot::RobotRunResult rf = robot::simulate(f);
  CHECK(rf.run.status == reduced::RunStatus::kDiverged);
  CHECK_THAT(rf.run.reason, Contains("h_fixed 10 s (verlet): expected a fixed step of at most"));
  CHECK(rf.run.t_end == 0.0);
  CHECK(rf.run.trajectory.size() == 1);
  CHECK(ex::all_finite(rf.run));
}

TEST_CASE("run limits: RK4 just inside the bound sees every touchdown the reference sees",
          "[run_limits]") {
  // Flights are parabolas, which RK4 and its cubic dense output follow exactly: at a step
  // just under half the flight, the touchdowns are the tight DOPRI5 run's, none skipped.
  const scene::Scene ref = test::load_shipped("case1_body_only");
  scene::Scene s = ref;
  s.simulation.solver.method = ode::Method::kRk4;
  s.simulation.solver.h_fixed = 0.99 * reduced::max_fixed_step(s);
  const reduced::RunResult a = reduced::simulate(ref), b = reduced::simulate(s);
  REQUIRE(a.status == reduced::RunStatus::kCompleted);
  REQUIRE(b.status == reduced::RunStatus::kCompleted);
  REQUIRE(a.strides.size() == b.strides.size());
  for (size_t k = 0; k < a.strides.size(); ++k) {
    CHECK(b.strides[k].t_touchdown == Approx(a.strides[k].t_touchdown).margin(1e-3));
  }
}
