// Robust design: scenarios that perturb the robot. The draws against their distributions'
// analytic moments, the plant against the hop law's closed form with the controller keeping the
// nominal numbers, and the bad inputs a study refuses.
#include <catch2/catch.hpp>

#include <cmath>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/perturbation.hpp"
#include "optimize/scenario.hpp"
#include "optimize/study.hpp"
#include "sim/simulate.hpp"

using namespace pronk;
using namespace pronk::optimize;
using nlohmann::json;

namespace {

std::string scene_path(const std::string& name) {
  std::string p = PRONK_SOURCE_DIR;
  p.append("/studies/scenes/").append(name);
  return p;
}

struct Moments {
  double mean = 0.0, variance = 0.0, lo = 1e300, hi = -1e300;
};

Moments moments_of(const PlantPerturbation& p, long n) {
  Moments m;
  std::vector<double> v;
  for (long i = 0; i < n; ++i) {
    const PlantDraw d = draw_perturbation(p, mix_seed(7, static_cast<std::uint64_t>(i)), 2);
    v.push_back(d.value);
    m.mean += d.value / static_cast<double>(n);
    m.lo = std::min(m.lo, d.value);
    m.hi = std::max(m.hi, d.value);
  }
  for (double x : v) m.variance += (x - m.mean) * (x - m.mean) / static_cast<double>(n - 1);
  return m;
}

// Variance of a normal N(0, s^2) truncated to [-a, a]: s^2 (1 - 2 al phi(al) / (2 Phi(al) - 1)),
// al = a / s.
double truncated_variance(double s, double a) {
  const double al = a / s;
  const double phi = std::exp(-0.5 * al * al) / std::sqrt(2.0 * M_PI);
  const double mass = std::erf(al / std::sqrt(2.0));  // 2 Phi(al) - 1
  return s * s * (1.0 - 2.0 * al * phi / mass);
}

// A body-only robot hopping in place from 0.1 m above its touchdown height.
scene::Scene hopper(const std::string& model) {
  json doc = {
      {"name", "hopper"},
      {"model", model},
      {"body", {{"mass", 1.5}, {"inertia", {0.0074, 0.0106, 0.0164}}}},
      {"legs", {{"kind", "body_only"}, {"length", 0.25}}},
      {"controller", {{"hop_height", 0.2}}},
      {"initial", {{"position", {0.0, 0.0, 0.35}}}},
      {"simulation",
       {{"duration", 4.0}, {"solver", {{"method", "dopri5"}, {"rtol", 1e-11}, {"atol", 1e-11}}}}}};
  if (model == "pulse") doc["pulse"] = {{"mode", "duration"}, {"duration", 0.05}};
  return io::parse_scene(doc, "hopper");
}

ScenarioSet one(const Scenario& s) {
  ScenarioSet set;
  set.scenarios = {s};
  set.duration = 4.0;
  return set;
}

// A study on `scene` whose random scenarios perturb the robot as `perturb` says.
json study_with(const std::string& scene, const json& perturb, const std::string& model = "") {
  json st = {
      {"name", "robust_test"},
      {"scene", scene_path(scene)},
      {"parameters",
       {{{"name", "kp_x"}, {"pointer", "/controller/kp/0"}, {"lower", 0.1}, {"upper", 10.0}}}},
      {"scenarios", {{"duration", 1.0}, {"random", {{"count", 2}, {"perturb", perturb}}}}},
      {"objective", {{{"metric", "x_error"}}}},
      {"stability", false},
      {"optimizer", {{"max_evaluations", 2}}}};
  if (!model.empty()) st["model"] = model;
  return st;
}

// The error a study with these perturbations gives (fails the test when there is none).
io::InputError refusal(const std::string& scene, const json& perturb,
                       const std::string& model = "") {
  try {
    parse_study(study_with(scene, perturb, model), "robust.json", ".");
  } catch (const io::InputError& e) {
    return e;
  }
  FAIL("no InputError");
  return io::InputError("", "", "", "");
}

}  // namespace

TEST_CASE("robot perturbations: uniform draws have the uniform's mean and variance",
          "[optimize][perturb]") {
  PlantPerturbation p{"/body/mass", true, -0.15, 0.15, false, 0.0};
  const long n = 20000;
  const Moments m = moments_of(p, n);
  const double var = 0.3 * 0.3 / 12.0;
  CHECK(std::abs(m.mean) < 4.0 * std::sqrt(var / n));
  CHECK(m.variance == Approx(var).epsilon(0.03));
  CHECK(m.lo >= -0.15);
  CHECK(m.hi <= 0.15);
  // Deterministic: the same (seed, index, k) gives the same bits; another k another number.
  const auto a = draw_perturbation(p, mix_seed(7, 11), 0);
  CHECK(a.value == draw_perturbation(p, mix_seed(7, 11), 0).value);
  CHECK(a.value != draw_perturbation(p, mix_seed(7, 11), 1).value);
}

TEST_CASE("robot perturbations: normal draws have the truncated normal's mean and variance",
          "[optimize][perturb]") {
  const long n = 20000;
  for (double sigma : {0.1, 0.3}) {
    PlantPerturbation p{"/pseudo_rigid/friction", false, 0.6, 1.2, true, sigma};
    const Moments m = moments_of(p, n);
    const double var = truncated_variance(sigma, 0.3);
    INFO("sigma " << sigma);
    CHECK(std::abs(m.mean - 0.9) < 4.0 * std::sqrt(var / n));
    CHECK(m.variance == Approx(var).epsilon(0.04));
    CHECK(m.lo >= 0.6);
    CHECK(m.hi <= 1.2);
  }
  // sigma 0.1 on +-0.3 is nearly the full normal: 0.01 x (1 - 0.0266).
  CHECK(truncated_variance(0.1, 0.3) == Approx(0.01 * (1 - 6 * 0.0044318 / 0.9973)).epsilon(1e-3));
}

TEST_CASE("robot perturbations leave the start draws of a scenario unchanged",
          "[optimize][perturb]") {
  RandomScenarios spec;
  spec.seed = 5;
  spec.tilt_lo = 0.0, spec.tilt_hi = 0.17;
  spec.lateral_lo = 0.0, spec.lateral_hi = 0.2;
  spec.kick_lo = 0.0, spec.kick_hi = 0.2;
  const Scenario plain = sample_scenario(spec, 3);
  spec.perturb = {{"/body/mass", true, -0.15, 0.15, false, 0.0},
                  {"/body/inertia_tensor", true, -0.2, 0.2, false, 0.0}};
  const Scenario robot = sample_scenario(spec, 3);
  CHECK(robot.tilt == plain.tilt);
  CHECK(robot.position_offset == plain.position_offset);
  CHECK(robot.velocity_kick == plain.velocity_kick);
  REQUIRE(robot.plant.size() == 2);
  CHECK(robot.plant[0].value == draw_perturbation(spec.perturb[0], mix_seed(5, 3), 0).value);
  CHECK(with_nominal_robot(one(robot)).scenarios[0].plant.empty());
  CHECK(perturbs_robot(one(robot)));
  CHECK_FALSE(perturbs_robot(one(plain)));
}

TEST_CASE("a perturbed robot keeps its nominal controller: numbers and gains",
          "[optimize][perturb]") {
  const scene::Scene nominal = io::load_scene(scene_path("pr_running.json"));
  Scenario s;
  s.plant = {{"/body/mass", true, 0.15},
             {"/body/inertia_tensor", true, -0.2},
             {"/pseudo_rigid/leg_stiffness", true, 0.1},
             {"/pseudo_rigid/friction", false, 0.6}};
  const scene::Scene plant = apply_scenario(nominal, s, one(s));
  CHECK(plant.body.mass == Approx(1.5 * 1.15).epsilon(1e-15));
  CHECK(plant.body.inertia(2, 2) == Approx(0.0164 * 0.8).epsilon(1e-15));
  CHECK(plant.pseudo_rigid.leg_stiffness ==
        Approx(nominal.pseudo_rigid.leg_stiffness * 1.1).epsilon(1e-15));
  CHECK(plant.pseudo_rigid.friction == 0.6);
  REQUIRE(plant.controller_model.has_value());
  CHECK(plant.controller_model->body.mass == nominal.body.mass);
  CHECK(plant.controller_model->body.inertia == nominal.body.inertia);
  CHECK(plant.controller_model->leg_stiffness == nominal.pseudo_rigid.leg_stiffness);
  // The gains were absolute before the perturbation: they do not follow the plant.
  CHECK(plant.controller.kp == nominal.controller.kp);
  CHECK(plant.controller.kd == nominal.controller.kd);
  CHECK(plant.pseudo_rigid.stance_kp[0] == nominal.pseudo_rigid.stance_kp[0]);
  // What the controller sees is the nominal robot.
  const scene::Scene seen = scene::controller_view(plant);
  CHECK(seen.body.mass == nominal.body.mass);
  CHECK(seen.pseudo_rigid.leg_stiffness == nominal.pseudo_rigid.leg_stiffness);
}

TEST_CASE("a heavier robot whose controller keeps the nominal mass hops as the hop law predicts",
          "[optimize][perturb]") {
  // Impulse model: at touchdown (z = l, vertical speed v0 < 0) the hop law asks
  // P = Kd_z (v1 - v0), Kd_z = m the nominal mass, v1 = sqrt(2 g h). The plant of mass m'
  // takes off at v+ = v0 + (m / m') (v1 - v0) and peaks v+^2 / (2 g) above l. Stride to
  // stride v+_k = r v1 - (1 - r) v+_{k-1}, r = m / m': a fixed point v1 r / (2 - r), the apex
  // h (r / (2 - r))^2 above l.
  const scene::Scene nominal = hopper("impulse");
  REQUIRE(nominal.controller.kd[2] == 1.5);
  Scenario s;
  s.plant = {{"/body/mass", true, 0.15}};
  const scene::Scene plant = apply_scenario(nominal, s, one(s));
  CHECK(plant.controller.kd[2] == 1.5);
  const RunResult r = simulate(plant);
  const double g = 9.81, l = 0.25, h = 0.2, ratio = 1.0 / 1.15, v1 = std::sqrt(2 * g * h);
  REQUIRE(r.run.strides.size() > 10);
  for (const auto& st : r.run.strides) {
    if (!st.has_apex) continue;
    const double v0 = st.velocity.z();
    const double up = v0 + ratio * (v1 - v0);
    CHECK(st.apex_height == Approx(l + up * up / (2 * g)).epsilon(1e-8));
  }
  const double fixed = ratio / (2 - ratio);
  double last = 0.0;
  for (const auto& st : r.run.strides)
    if (st.has_apex) last = st.apex_height;
  CHECK(last == Approx(l + h * fixed * fixed).epsilon(1e-6));
  CHECK(fixed * fixed * h == Approx(0.11834).epsilon(1e-3));  // 8.2 cm short of 0.2 m
}

TEST_CASE("the pulse model's gravity compensation uses the controller's nominal mass",
          "[optimize][perturb]") {
  // Body-only pulse, duration T: the controller asks P = m (v1 - v0) + m g T over T with its
  // nominal m; the plant m' takes off at v+ = v0 + r (v1 - v0) + (r - 1) g T (r = m / m') after
  // rising (v0 + v+) T / 2 in the stance, and peaks v+^2 / (2 g) higher.
  const scene::Scene nominal = hopper("pulse");
  Scenario s;
  s.plant = {{"/body/mass", true, 0.15}};
  const RunResult r = simulate(apply_scenario(nominal, s, one(s)));
  const double g = 9.81, l = 0.25, T = 0.05, ratio = 1.0 / 1.15, v1 = std::sqrt(2 * g * 0.2);
  long checked = 0;
  for (const auto& st : r.run.strides) {
    if (!st.has_apex) continue;
    const double v0 = st.velocity.z();
    const double up = v0 + ratio * (v1 - v0) + (ratio - 1) * g * T;
    CHECK(st.apex_height == Approx(l + (v0 + up) * T / 2 + up * up / (2 * g)).epsilon(1e-8));
    ++checked;
  }
  CHECK(checked > 10);
}

TEST_CASE("the full model's controller reads the nominal numbers, the dynamics the perturbed",
          "[optimize][perturb]") {
  scene::Scene nominal = io::load_scene(scene_path("pr_running.json"));
  nominal.simulation.duration = 1.5;
  // A controller model equal to the robot changes nothing, to the bit.
  scene::Scene same = nominal;
  same.controller_model = scene::controller_model_of(nominal);
  const RunResult a = simulate(nominal), b = simulate(same);
  REQUIRE(a.run.strides.size() == b.run.strides.size());
  CHECK(a.run.strides.back().apex_height == b.run.strides.back().apex_height);
  // A heavier robot: a controller that keeps the nominal mass runs otherwise than one that
  // is told the new mass (its rebound, thrust and stance-time laws read the mass).
  Scenario s;
  s.plant = {{"/body/mass", true, 0.15}};
  const scene::Scene keeps = apply_scenario(nominal, s, one(s));
  scene::Scene told = keeps;
  told.controller_model.reset();
  const RunResult k = simulate(keeps), t = simulate(told);
  REQUIRE(k.run.strides.size() > 1);
  REQUIRE(t.run.strides.size() > 1);
  CHECK(k.run.strides[1].apex_height != t.run.strides[1].apex_height);
}

TEST_CASE("actuation and sensing errors are drawn like any number of the robot",
          "[optimize][perturb]") {
  // Both are left out of the resolved scene at their defaults (1, 0): a study still names them.
  parse_study(study_with("pr_running.json",
                         {{{"pointer", "/pseudo_rigid/actuator_gain"}, {"relative", {-0.1, 0.1}}},
                          {{"pointer", "/pseudo_rigid/attitude_sensor_bias_deg/1"},
                           {"range", {-1.0, 1.0}}}}),
              "robust.json", ".");
  const scene::Scene nominal = io::load_scene(scene_path("pr_running.json"));
  Scenario s;
  s.plant = {{"/pseudo_rigid/actuator_gain", true, -0.1},
             {"/pseudo_rigid/attitude_sensor_bias_deg/1", false, 0.5}};
  const scene::Scene plant = apply_scenario(nominal, s, one(s));
  CHECK(plant.pseudo_rigid.actuator_gain == Approx(0.9).epsilon(1e-15));
  CHECK(plant.pseudo_rigid.attitude_sensor_bias[1] == Approx(0.5 * M_PI / 180.0).epsilon(1e-15));
  CHECK(plant.pseudo_rigid.attitude_sensor_bias[0] == 0.0);
  // The pulse model has neither: refused there, as its ignored numbers are.
  const auto e = refusal("case3_legged_pulse.json",
                         {{{"pointer", "/pseudo_rigid/actuator_gain"}, {"range", {0.9, 1.1}}}});
  CHECK(e.expected() == "a number the pulse model uses");
}

TEST_CASE(
    "a study refuses robot perturbations that name nothing, that the model ignores or that "
    "make the robot unphysical",
    "[optimize][perturb]") {
  const std::string at = "/scenarios/random/perturb/0";
  {
    const auto e = refusal("case3_legged_pulse.json",
                           {{{"pointer", "/body/nope"}, {"relative", {-0.1, 0.1}}}});
    CHECK(e.pointer() == at + "/pointer");
    CHECK(e.found() == "\"/body/nope\", which names nothing");
  }
  {
    const auto e = refusal("case3_legged_pulse.json",
                           {{{"pointer", "/pseudo_rigid/friction"}, {"range", {0.6, 1.2}}}});
    CHECK(e.pointer() == at + "/pointer");
    CHECK(e.expected() == "a number the pulse model uses");
  }
  {
    const auto e =
        refusal("case3_legged_pulse.json", {{{"pointer", "/body/mass"}, {"range", {0.0, 2.0}}}});
    CHECK(e.pointer() == at + "/range");
    CHECK(e.expected() == "a range that keeps /body/mass > 0");
  }
  {
    const auto e = refusal("case3_legged_pulse.json",
                           {{{"pointer", "/body/mass"}, {"relative", {-1.0, 0.1}}}});
    CHECK(e.pointer() == at + "/relative");
  }
  {
    const auto e =
        refusal("pr_running.json",
                {{{"pointer", "/pseudo_rigid/leg_stiffness"}, {"range", {-10.0, 500.0}}}});
    CHECK(e.expected() == "a range that keeps /pseudo_rigid/leg_stiffness > 0");
  }
  {
    // 0.0164 x 1.2 > (0.0074 + 0.0106) x 0.8: a flat body's moments cannot move apart by 20 %.
    const auto e = refusal("case3_legged_pulse.json",
                           {{{"pointer", "/body/inertia_tensor/0/0"}, {"relative", {-0.2, 0.2}}},
                            {{"pointer", "/body/inertia_tensor/1/1"}, {"relative", {-0.2, 0.2}}},
                            {{"pointer", "/body/inertia_tensor/2/2"}, {"relative", {-0.2, 0.2}}}});
    CHECK(e.pointer() == "/scenarios/random/perturb");
    CHECK_THAT(e.expected(), Catch::Matchers::Contains("triangle inequality"));
    CHECK_THAT(e.found(), Catch::Matchers::Contains("Izz"));
  }
  {
    const auto e = refusal("case3_legged_pulse.json",
                           {{{"pointer", "/body/inertia_tensor/0/1"}, {"relative", {-0.2, 0.2}}}});
    CHECK(e.pointer() == at + "/pointer");
  }
  {
    const auto e = refusal("case3_legged_pulse.json", {{{"pointer", "/body/mass"},
                                                        {"relative", {-0.1, 0.1}},
                                                        {"distribution", "normal"},
                                                        {"sigma", 0.5}}});
    CHECK(e.pointer() == at + "/sigma");
  }
  // The whole inertia scaled by +-20 % keeps its shape: accepted, with the start draws.
  const Study st =
      parse_study(study_with("case3_legged_pulse.json",
                             {{{"pointer", "/body/inertia_tensor"}, {"relative", {-0.2, 0.2}}},
                              {{"pointer", "/body/mass"}, {"relative", {-0.15, 0.15}}}}),
                  "robust.json", ".");
  REQUIRE(st.evaluator.scenarios.scenarios.size() == 2);
  CHECK(st.evaluator.scenarios.scenarios[0].plant.size() == 2);
}
