// pronk design's derived study: its rules checked against their closed forms (the duty axis,
// the legs' stance spring and damping ratio), and the study it writes is one the staged-study
// reader accepts as it is.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/design/design_study.hpp"
#include "optimize/staged_study.hpp"

using namespace pronk;
using namespace pronk::optimize;
using nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string family(const std::string& name) {
  return std::string(PRONK_SOURCE_DIR) + "/studies/scenes/family/" + name + ".json";
}

const json& parameter(const json& study, const std::string& name) {
  for (const auto& p : study.at("parameters")) {
    if (p.at("name") == name) return p;
  }
  FAIL("no parameter " << name);
  static json none;
  return none;
}

}  // namespace

TEST_CASE("pronk design: the pulse duration spans the duty range on the robot's own flight",
          "[design]") {
  for (const char* robot : {"tripod", "mini_quad", "hexapod"}) {
    INFO(robot);
    const json scene = io::read_json_file(family(robot));
    const json study = derive_design_study(scene, family(robot), "scene.json", DesignOptions{});
    // Flight of the hop height h: 2 sqrt(2 g h) / g; duty d = Ts / (Ts + Tf).
    const double h = scene.at("controller").at("hop_height");
    const double tf = 2.0 * std::sqrt(2.0 * 9.81 * h) / 9.81;
    const json& p = parameter(study, "pulse_duration");
    const double lo = p.at("lower"), hi = p.at("upper"), start = p.at("initial");
    CHECK(lo / (lo + tf) == Approx(0.14).epsilon(1e-12));
    CHECK(hi / (hi + tf) == Approx(0.26).epsilon(1e-12));
    CHECK(start / (start + tf) == Approx(0.2).epsilon(1e-12));
  }
}

TEST_CASE("pronk design: leg stiffness and damping follow the stance spring of the robot",
          "[design]") {
  const json scene = io::read_json_file(family("hexapod"));
  const json study = derive_design_study(scene, family("hexapod"), "scene.json", DesignOptions{});
  const double m = 5.0, n = 6.0, h = 0.4;
  const double tf = 2.0 * std::sqrt(2.0 * 9.81 * h) / 9.81;
  auto stance = [&](double d) { return d * tf / (1.0 - d); };
  auto k_for = [&](double ts) { return m * std::pow(kPi / ts, 2) / n; };  // pi sqrt(m/(n k)) = Ts
  const json& k = parameter(study, "leg_stiffness");
  CHECK(k.at("lower").get<double>() == Approx(0.5 * k_for(stance(0.26))).epsilon(1e-12));
  CHECK(k.at("upper").get<double>() == Approx(2.0 * k_for(stance(0.14))).epsilon(1e-12));
  CHECK_FALSE(k.contains("initial"));  // the full stage starts it from the pulse stage's Ts
  const double critical = 2.0 * std::sqrt(k_for(stance(0.2)) * m / n);
  const json& c = parameter(study, "leg_damping");
  CHECK(c.at("initial").get<double>() == Approx(0.2 * critical).epsilon(1e-12));
  CHECK(c.at("lower").get<double>() == Approx(0.05 * critical).epsilon(1e-12));
}

TEST_CASE("pronk design: the derived study is a staged study as written", "[design]") {
  for (const char* robot : {"tripod", "mini_quad", "pentapod", "hexapod", "sidestep_quad"}) {
    INFO(robot);
    json scene = io::read_json_file(family(robot));
    DesignOptions o;
    json study = derive_design_study(scene, family(robot), "scene.json", o);
    // Inline the scene (the study refers to DIR/scene.json) and read it as pronk optimize does.
    study["scene"] = scene;
    const StagedStudy st = parse_staged_study(study, "study.json", ".");
    REQUIRE(st.stages.size() == 2);
    CHECK(st.stages[0].model == "pulse");
    CHECK(st.stages[1].model == "pseudo_rigid");
    CHECK(st.leg_stiffness_follows);
    // Every parameter starts inside its bounds (the reader refuses one that does not).
    for (const auto& p : study.at("parameters")) {
      INFO(p.at("name").get<std::string>());
      CHECK(p.at("lower").get<double>() < p.at("upper").get<double>());
      if (!p.contains("initial")) continue;
      CHECK(p.at("initial").get<double>() >= p.at("lower").get<double>());
      CHECK(p.at("initial").get<double>() <= p.at("upper").get<double>());
    }
    CHECK(st.parameters.size() == study.at("parameters").size());
    // Every validation trial perturbs the robot: mass, inertia, legs, friction.
    const json& perturb = study.at("validation").at("random").at("perturb");
    CHECK(perturb.size() == 4);
    CHECK(study.at("stages").at(0).at("scenarios").at("random").at("perturb").size() == 2);
  }
}

TEST_CASE("pronk design: a scene with its own pulse section gets the derived pulse duration",
          "[design]") {
  // pr_running gives "pulse": the derived study overrides its duration with a JSON number.
  const std::string file = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json";
  json scene = io::read_json_file(file);
  json study = derive_design_study(scene, file, "scene.json", DesignOptions{});
  study["scene"] = scene;
  const StagedStudy st = parse_staged_study(study, "study.json", ".");
  const json& p = parameter(study, "pulse_duration");
  const double tf = 2.0 * std::sqrt(2.0 * 9.81 * 0.2) / 9.81;
  const double start = p.at("initial");
  CHECK(start / (start + tf) == Approx(0.2).epsilon(1e-12));
  bool found = false;
  for (const auto& o : study.at("scene_overrides")) {
    const std::string s = o.get<std::string>();
    if (s.rfind("/pulse/duration=", 0) != 0) continue;
    found = true;
    CHECK(std::stod(s.substr(16)) == Approx(start).epsilon(1e-15));
  }
  CHECK(found);
  CHECK(st.stages.size() == 2);
}

TEST_CASE("pronk design: the attitude trim's limit is raised unless the scene sets its own",
          "[design]") {
  // The limit the derived study's full model runs with, read back from the scene it resolves.
  auto limit = [](json scene, const std::string& file) {
    json study = derive_design_study(scene, file, "scene.json", DesignOptions{});
    for (const auto& o : study.at("scene_overrides")) io::apply_override(scene, o);
    return io::parse_scene(scene, file).pseudo_rigid.attitude_trim_max;
  };
  const json tripod = io::read_json_file(family("tripod"));  // no pseudo_rigid section
  CHECK(limit(tripod, family("tripod")) == 0.4);
  const std::string pr = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json";
  json pr_running = io::read_json_file(pr);  // its own pseudo_rigid section, no limit
  REQUIRE(pr_running.at("pseudo_rigid").is_object());
  CHECK(limit(pr_running, pr) == 0.4);
  pr_running["pseudo_rigid"]["attitude_trim_max"] = 0.25;  // the scene's own limit stays
  CHECK(limit(pr_running, pr) == 0.25);
  CHECK(io::parse_scene(tripod, family("tripod")).pseudo_rigid.attitude_trim_max == 0.2);
}

TEST_CASE("pronk design: --tune-nominal keeps the tuning robot nominal, not the validation",
          "[design]") {
  const json scene = io::read_json_file(family("tripod"));
  DesignOptions o;
  o.tune_nominal = true;
  const json study = derive_design_study(scene, family("tripod"), "scene.json", o);
  CHECK_FALSE(study.at("scenarios").at("random").contains("perturb"));
  CHECK_FALSE(study.at("stages").at(0).at("scenarios").at("random").contains("perturb"));
  CHECK(study.at("validation").at("random").at("perturb").size() == 4);
}

TEST_CASE("pronk design: a scene without legs or bad options are bad input", "[design]") {
  const json body_only = json::parse(R"({"body": {"mass": 1}, "legs": {"kind": "body_only"}})");
  try {
    derive_design_study(body_only, "robot.json", "scene.json", DesignOptions{});
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(e.file() == "robot.json");
    CHECK(e.pointer() == "/legs/kind");
    CHECK_THAT(e.what(), Catch::Matchers::Contains("a legged robot"));
  }
  const json scene = io::read_json_file(family("tripod"));
  DesignOptions o;
  o.duty_lo = 0.3;  // above the start and the upper bound
  CHECK_THROWS_AS(derive_design_study(scene, family("tripod"), "scene.json", o), io::InputError);
}
