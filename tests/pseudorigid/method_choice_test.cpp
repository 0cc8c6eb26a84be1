// "method": "auto" (sim/pseudorigid/method_choice.hpp): each rule on probes made for it, the
// choice on every shipped mechanism scene and on pr_running (verlet at 0.8 x its stability
// limit, rounded down to two digits), and the chosen runs meeting the accuracy target
// (largest sampled energy-balance drift within 1e-3 of the energy scale).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/method_choice.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/robot/robot_simulator.hpp"

namespace pr = pronk::pseudorigid;
namespace io = pronk::io;
using pronk::ode::Method;

namespace {

const std::string kRoot = std::string(PRONK_SOURCE_DIR);

pr::SceneProbe probe(double omega, bool contact, bool dissipation) {
  pr::SceneProbe p;
  p.omega_max = omega;
  p.omega_bound = 1.2 * omega;
  p.min_mass = 0.01;
  p.contact = contact;
  p.dissipation = dissipation;
  p.springs = omega > 0.0 ? 1 : 0;
  return p;
}

pr::AutoRequest request(double accuracy) {
  pr::AutoRequest r;
  r.accuracy = accuracy;
  return r;
}

/// The shipped mechanism with "method": "auto" (and t_end when > 0).
io::LoadedMechanism load_auto(const std::string& file, double t_end = 0.0) {
  nlohmann::json doc = io::read_json_file(file);
  doc["simulation"]["method"] = "auto";
  for (const char* k : pr::kAutoChosenSettings) doc["simulation"].erase(k);  // auto's to choose
  if (t_end > 0.0) doc["simulation"]["t_end"] = t_end;
  return io::parse_mechanism(doc, file);
}

}  // namespace

TEST_CASE("auto: each rule on its probe", "[pseudorigid][auto]") {
  // 1. No springs: dopri5 at a tenth of the budget.
  pr::MethodChoice c = pr::choose_method(probe(0.0, false, false), request(1e-3));
  CHECK(c.method == Method::kDopri5);
  CHECK(c.rule == 1);
  CHECK(c.rtol == Approx(1e-4));
  // 2. A budget below 1e-6: radau5, or rodas4 with contact.
  c = pr::choose_method(probe(1e3, false, false), request(1e-7));
  CHECK(c.method == Method::kRadau5);
  CHECK(c.rule == 2);
  CHECK(pr::choose_method(probe(1e3, true, false), request(1e-7)).method == Method::kRodas4);
  // 3. Dampers verlet can only take explicitly: rodas4.
  pr::SceneProbe p = probe(1e3, false, true);
  p.dissipation_split = false;
  c = pr::choose_method(p, request(1e-3));
  CHECK(c.method == Method::kRodas4);
  CHECK(c.rule == 3);
  // 4. Stiffer than 0.8 x 2 / omega = 2e-5 s: radau5, cost flat in the stiffness.
  c = pr::choose_method(probe(1e5, true, false), request(1e-3));
  CHECK(c.method == Method::kRadau5);
  CHECK(c.rule == 4);
  CHECK(c.rtol == Approx(1e-5));
  // 5. The stiffest mode an elastic contact: dopri5 at a x 1e-4.
  p = probe(1e3, true, false);
  p.omega_elastic_contact = 1e3;
  c = pr::choose_method(p, request(1e-3));
  CHECK(c.method == Method::kDopri5);
  CHECK(c.rule == 5);
  CHECK(c.rtol == Approx(1e-7));
  // 6. Otherwise verlet at 0.8 x 2 / omega rounded down to two digits, budget a / 2.
  c = pr::choose_method(probe(2000.0, true, true), request(1e-3));
  CHECK(c.method == Method::kVerlet);
  CHECK(c.rule == 6);
  CHECK(c.h_fixed == Approx(8e-4));
  CHECK(c.energy_tol == Approx(5e-4));
  c = pr::choose_method(probe(3162.3, true, false), request(1e-3));
  CHECK(c.h_fixed == Approx(5e-4));  // 5.06e-4 rounded down
  // ... at most h_max.
  pr::AutoRequest r = request(1e-3);
  r.h_max = 1e-4;
  CHECK(pr::choose_method(probe(2000.0, true, false), r).h_fixed == Approx(1e-4));
  // 7. Smooth (no contact): radau5 at a tenth of the budget, before rules 4 and 6.
  c = pr::choose_method(probe(2000.0, false, false), request(1e-3));
  CHECK(c.method == Method::kRadau5);
  CHECK(c.rule == 7);
  CHECK(c.rtol == Approx(1e-4));
  // 8. A robot (restarts) without contact: dopri5 at a / 1000 while its stability limit
  // 3.3 / omega stays above 8e-5 s (omega < 41 250 rad/s), radau5 beyond; before rule 7.
  pr::AutoRequest robot = request(1e-3);
  robot.restarts = true;
  c = pr::choose_method(probe(2000.0, false, false), robot);
  CHECK(c.method == Method::kDopri5);
  CHECK(c.rule == 8);
  CHECK(c.rtol == Approx(1e-6));
  CHECK(pr::choose_method(probe(41000.0, false, false), robot).method == Method::kDopri5);
  c = pr::choose_method(probe(42000.0, false, false), robot);
  CHECK(c.method == Method::kRadau5);
  CHECK(c.rule == 8);
  CHECK(c.rtol == Approx(1e-6));
  // 4. for a robot with contact: rodas4, not radau5, at a / 100 (its contacts switch).
  c = pr::choose_method(probe(1e5, true, true), robot);
  CHECK(c.method == Method::kRodas4);
  CHECK(c.rule == 4);
  CHECK(c.rtol == Approx(1e-5));
  c = pr::choose_method(probe(1e5, true, true), request(1e-3));
  CHECK(c.method == Method::kRadau5);
  CHECK(c.rule == 4);
  // ... and verlet with restarts at 0.7 x its limit, energy_tol 0, below that stiffness.
  c = pr::choose_method(probe(1e4, true, true), robot);
  CHECK(c.method == Method::kVerlet);
  CHECK(c.h_fixed == Approx(1.4e-4));
  CHECK(c.energy_tol == 0.0);
  // The reason is one line and names the choice and its grounds.
  c = pr::choose_method(probe(2000.0, true, true), request(1e-3));
  CHECK(c.reason.find('\n') == std::string::npos);
  CHECK(c.reason.rfind("auto: verlet h=0.0008 s", 0) == 0);
  CHECK(c.reason.find("non-smooth contact") != std::string::npos);
  CHECK(c.reason.find("energy budget 0.001") != std::string::npos);
}

TEST_CASE("auto on the shipped mechanism scenes: verlet, and the run meets its budget",
          "[pseudorigid][auto]") {
  // Expected: the scenes without contact rule 7 (radau5 at 1e-4); four_leg_drop rule 6
  // (verlet, h = 0.8 x 2 / omega_max rounded down to two digits; omega_max checked against
  // verlet's real limit in scene_probe_test.cpp); spring_leg_drop, whose stiffest mode is
  // its elastic ground contact, rule 5 (dopri5 at 1e-7).
  const std::map<std::string, double> expected_h = {{"four_leg_drop", 4.7e-4}};
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(kRoot + "/studies/mechanisms")) {
    if (e.path().extension() != ".json") continue;
    const std::string name = e.path().stem().string();
    INFO(name);
    const io::LoadedMechanism l = load_auto(e.path().string());
    REQUIRE(l.method_auto);
    const pr::MethodChoice& c = l.method_choice;
    CHECK(l.mechanism.simulation.solver.method == c.method);
    if (name == "spring_leg_drop") {
      CHECK(c.method == Method::kDopri5);
      CHECK(c.rule == 5);
      CHECK(c.rtol == Approx(1e-7));
      CHECK(l.mechanism.simulation.solver.rtol == c.rtol);
    } else if (name != "four_leg_drop") {
      CHECK(c.method == Method::kRadau5);
      CHECK(c.rule == 7);
      CHECK(c.rtol == Approx(1e-4));
      CHECK(l.mechanism.simulation.solver.rtol == c.rtol);
    } else {
      CHECK(c.method == Method::kVerlet);
      CHECK(c.rule == 6);
      REQUIRE(expected_h.count(name) == 1);
      CHECK(c.h_fixed == Approx(expected_h.at(name)));
      CHECK(l.mechanism.simulation.solver.h_fixed == c.h_fixed);
      CHECK(l.mechanism.simulation.energy_tol == c.energy_tol);
    }
    // The whole shipped run (its own t_end) meets the default budget.
    const pr::RunSummary run = pr::simulate(l.mechanism);
    CHECK(run.status == pr::RunStatus::kCompleted);
    CHECK(run.energy_drift <= c.accuracy * run.energy_scale);
    // Deterministic: the same document, the same choice.
    CHECK(load_auto(e.path().string()).method_choice.reason == c.reason);
    ++n;
  }
  CHECK(n == 5);
}

TEST_CASE("auto on pr_running: verlet below the feet's limit, within the budget",
          "[pseudorigid][auto][robot]") {
  pronk::scene::Scene s =
      io::load_scene(kRoot + "/studies/scenes/pr_running.json",
                     {"/simulation/duration=3", R"(/pseudo_rigid/solver={"method": "auto"})"});
  REQUIRE(s.pseudo_rigid.solver_auto);
  const pronk::robot::RobotRunResult r = pronk::robot::simulate(s);
  const pronk::robot::RobotMonitors& m = r.monitors;
  REQUIRE(m.method_auto);
  CHECK(m.method_choice.method == Method::kVerlet);
  // The 1 g feet on their 1e5 N/m slides: verlet diverges at 2e-4 s and completes at 1.75e-4 s
  // (docs/pseudorigid.md); the probe puts the limit at 1.8e-4 s.
  CHECK(2.0 / m.method_choice.probe.omega_max == Approx(1.8e-4).epsilon(0.05));
  CHECK(m.method_choice.h_fixed == Approx(1.2e-4));  // 0.7 x the limit (restarts)
  CHECK(r.run.status == pronk::reduced::RunStatus::kCompleted);
  CHECK(m.energy_drift <= 1e-3 * m.energy_scale);
}

TEST_CASE("auto's rerun: the knob scaled to aim at half the budget, once", "[pseudorigid][auto]") {
  // Verlet with a budget: energy_tol x 0.5 a / drift.
  pr::MethodChoice c = pr::choose_method(probe(2000.0, true, false), request(1e-3));
  REQUIRE(c.method == Method::kVerlet);
  REQUIRE(c.energy_tol == Approx(5e-4));
  CHECK_FALSE(pr::needs_rerun(c, 1e-3));  // met (at the bar)
  CHECK(pr::needs_rerun(c, 4e-3));
  pr::MethodChoice r = pr::refine_choice(c, 4e-3);
  CHECK(r.energy_tol == Approx(5e-4 * 0.5 * 1e-3 / 4e-3));
  CHECK(r.h_fixed == c.h_fixed);
  CHECK(r.reruns == 1);
  CHECK(r.first_drift == 4e-3);
  CHECK(r.reason.rfind(c.reason, 0) == 0);
  CHECK(r.reason.find("; rerun: the first run drifted 0.004 > 0.001, energy_tol 0.0005 -> "
                      "6.3e-05") != std::string::npos);
  CHECK(r.reason.find('\n') == std::string::npos);
  CHECK_FALSE(pr::needs_rerun(r, 1.0));  // once only
  // Verlet without a budget (a robot): h x sqrt(0.5 a / drift), rounded down to two digits.
  pr::AutoRequest robot = request(1e-3);
  robot.restarts = true;
  c = pr::choose_method(probe(1e4, true, true), robot);
  REQUIRE(c.energy_tol == 0.0);
  r = pr::refine_choice(c, 2e-3);
  CHECK(r.h_fixed == Approx(0.7e-4));  // 1.4e-4 x sqrt(0.25)
  CHECK(r.energy_tol == 0.0);
  // Adaptive methods: rtol = atol x 0.5 a / drift, at most a factor 1000 at once.
  c = pr::choose_method(probe(2000.0, false, false), request(1e-3));
  REQUIRE(c.method == Method::kRadau5);
  r = pr::refine_choice(c, 5e-3);
  CHECK(r.rtol == Approx(1e-4 * 0.1));
  CHECK(r.atol == r.rtol);
  CHECK(pr::refine_choice(c, 1e3).rtol == Approx(1e-7));  // capped
  // A non-finite drift never asks for a rerun (the run reports it instead).
  CHECK_FALSE(pr::needs_rerun(c, std::nan("")));
}
