// Map study files: axes (lists, linear and log ranges, derived axes), the
// duty-cycle definition, and bad input naming file, JSON Pointer, expected, found.
#include "optimize/map/map_study.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include "sim/scene/scene.hpp"

#include "io/load/input_error.hpp"
#include "optimize/map/map_engine.hpp"
#include "tests/optimize/map/map_test_support.hpp"

using nlohmann::json;
using pronk::io::InputError;
namespace m = pronk::optimize::map;

namespace {

// The error a document raises (file, pointer, expected), or "" if none.
std::string error_of(const json& doc) {
  try {
    m::parse_map_study(doc, "s.json", ".");
  } catch (const InputError& e) {
    return e.file() + ": " + e.pointer() + ": " + e.expected() + " | " + e.found();
  }
  return "";
}

}  // namespace

TEST_CASE("map axes: ranges, log spacing, lists and derived kinds", "[map][input]") {
  json doc = pronk::test::tiny_map_document(5);
  m::MapStudy st = m::parse_map_study(doc, "s.json", ".");
  REQUIRE(st.axes.size() == 2);
  CHECK(st.axes[0].values == std::vector<double>{0.2, 0.25, 0.3, 0.35, 0.4});
  CHECK(st.axes[1].kind == m::AxisKind::kTilt);
  CHECK(st.cells() == 10);
  CHECK(st.models.size() == 2);
  CHECK(st.primary_model() == pronk::scene::ModelKind::kPulse);
  CHECK(st.resolution == Approx(0.01));
  // Default resolution: 1/8 of the spacing.
  doc.erase("boundary");
  CHECK(m::parse_map_study(doc, "s.json", ".").resolution == Approx(0.05 / 8));
  doc["axes"][0] = {{"kind", "pointer"},
                    {"pointer", "/controller/bank/kp"},
                    {"range", {0.01, 1}},
                    {"count", 3},
                    {"scale", "log"}};
  st = m::parse_map_study(doc, "s.json", ".");
  CHECK(st.axes[0].values == std::vector<double>{0.01, 0.1, 1});
  CHECK(st.axes[0].log_scale);
}

TEST_CASE("the duty axis sets T = duty x (T + 2 sqrt(2h/g))", "[map]") {
  const m::MapStudy st = pronk::test::tiny_map();
  const double flight = 2.0 * std::sqrt(2.0 * 0.2 / 9.81);
  for (double d : {0.1, 0.3, 0.5}) {
    const double T = m::pulse_duration_for_duty(st.base_scene, d);
    CHECK(T / (T + flight) == Approx(d).epsilon(1e-14));
  }
}

TEST_CASE("the duty axis sets the leg stiffness where the full model times its own thrust",
          "[map]") {
  // Spring legs on the energy thrust: the pulse duration is unused in the full model, so the
  // duty axis sets the leg spring whose stance half-period pi sqrt(m / (n k)) is the pulse
  // model's T at that duty; the pulse model beside it still gets T.
  json doc = pronk::test::tiny_map_document(2, 1, 6.0);
  doc["models"] = {"pulse", "pseudo_rigid"};
  doc["scene_overrides"].push_back(R"(/pseudo_rigid={"legs": "spring", "thrust": "energy"})");
  const m::MapStudy st = m::parse_map_study(doc, "s.json", ".");
  for (double duty : {0.2, 0.4}) {
    const pronk::scene::Scene full =
        m::scene_at(st, duty, 0.0, pronk::scene::ModelKind::kPseudoRigid);
    const pronk::scene::Scene pulse = m::scene_at(st, duty, 0.0, pronk::scene::ModelKind::kPulse);
    CHECK(m::duty_setting(full) == m::DutySetting::kLegStiffness);
    CHECK(m::duty_setting(pulse) == m::DutySetting::kPulseDuration);
    const double T = m::pulse_duration_for_duty(st.base_scene, duty);
    CHECK(pulse.pulse.duration == Approx(T).epsilon(1e-14));
    const double k = full.pseudo_rigid.leg_stiffness;
    const double n = static_cast<double>(full.legs.hips.size());
    CHECK(M_PI * std::sqrt(full.body.mass / (n * k)) == Approx(T).epsilon(1e-12));
    CHECK(full.pulse.duration == st.base_scene.pulse.duration);  // untouched
  }
  // The impulse thrust uses the pulse duration: the duty axis sets it, as for the pulse model.
  doc["scene_overrides"].back() = R"(/pseudo_rigid={"legs": "spring", "thrust": "impulse"})";
  const m::MapStudy st2 = m::parse_map_study(doc, "s.json", ".");
  const pronk::scene::Scene full2 =
      m::scene_at(st2, 0.3, 0.0, pronk::scene::ModelKind::kPseudoRigid);
  CHECK(m::duty_setting(full2) == m::DutySetting::kPulseDuration);
  CHECK(full2.pulse.duration == Approx(m::pulse_duration_for_duty(st2.base_scene, 0.3)));
  CHECK(full2.pseudo_rigid.leg_stiffness == st2.base_scene.pseudo_rigid.leg_stiffness);
}

TEST_CASE("bad map studies name the file, the pointer, what was expected and found",
          "[map][input]") {
  json doc = pronk::test::tiny_map_document();
  CHECK(error_of(doc).empty());
  json d = doc;
  d["kind"] = "study";
  CHECK(error_of(d).find("s.json: /kind: \"map\"") == 0);
  d = doc;
  d["trials"]["cuont"] = 3;
  CHECK(error_of(d).find("s.json: /trials/cuont: a known key") == 0);
  d = doc;
  d["axes"][0] = {{"kind", "duty_cycle"}, {"values", {0.2, 0.3, 0.3}}};
  CHECK(error_of(d).find("s.json: /axes/0/values/2: strictly increasing") == 0);
  d = doc;
  d["axes"][0] = {{"kind", "duty_cycle"}, {"values", {0.2, 0.99}}};
  CHECK(error_of(d).find("s.json: /axes/0/values") == 0);
  d = doc;
  d["axes"][0] = {{"kind", "pointer"}, {"pointer", "/controller/nothing"}, {"values", {1, 2}}};
  CHECK(error_of(d).find("s.json: /axes/0/pointer: a pointer to a number") == 0);
  d = doc;
  d["axes"][0] = {{"kind", "pointer"}, {"pointer", "/body/mass"}, {"values", {1, -2}}};
  CHECK(error_of(d).find("s.json: /axes/0/values/1:") == 0);
  d = doc;
  d["axes"][0] = {{"kind", "pointer"}, {"pointer", "/body/mass"}, {"values", {-1, 2}}};
  CHECK(error_of(d).find("s.json: /axes/0/values/0: a value that makes a valid scene") == 0);
  d = doc;
  d["axes"][0] = {{"kind", "duty_cycle"}, {"range", {0.1, 0.5}}};
  d["axes"][0]["values"] = {0.1};
  CHECK(error_of(d).find("s.json: /axes/0/values: exactly one of") == 0);
  d = doc;
  d["axes"][1] = {{"kind", "disturbance_direction_deg"}, {"values", {0, 90}}};
  CHECK(error_of(d).find("s.json: /axes/1/magnitude: a kick size > 0") == 0);
  d = doc;
  d["models"] = {"pulse", "rigid"};
  CHECK(error_of(d).find(std::string("s.json: /models/1: \"impulse\", \"pulse\"") +
                         (pronk::scene::mujoco_available() ? ", \"pseudo_rigid\" or \"mujoco\" | "
                                                           : " or \"pseudo_rigid\" (this pronk")) ==
        0);
  d["models"] = {"pseudo_rigid", "pseudo_rigid"};
  CHECK(error_of(d).find("s.json: /models: two different models") == 0);
  if (pronk::scene::mujoco_available()) {  // the cells' model set past the scene's check
    d["models"] = {"pseudo_rigid", "mujoco"};
    d["scene_overrides"].push_back("/pseudo_rigid={\"feet\": \"quasi_static\"}");
    CHECK(error_of(d).find("/pseudo_rigid/feet: \"mass\" (MuJoCo's feet are bodies") !=
          std::string::npos);
  }
  d = doc;
  d["scene_overrides"].push_back("/pulse/mode=max_force");
  CHECK(error_of(d).find("/pulse/mode: \"duration\"") != std::string::npos);
  d = doc;
  d["axes"][0]["magnitude"] = 0.3;  // only a direction axis has a kick size
  CHECK(error_of(d).find("s.json: /axes/0/magnitude: no \"magnitude\" on a \"duty_cycle\" axis") ==
        0);
  d = doc;
  d["axes"] = json::array();
  CHECK(error_of(d).find("s.json: /axes: an array of one or two axes") == 0);
}

TEST_CASE("a map study may run the robot in the full model (pseudo_rigid)", "[map][input]") {
  json doc = pronk::test::tiny_map_document();
  doc["models"] = {"pulse", "pseudo_rigid"};
  doc["scene_overrides"].push_back(R"(/pseudo_rigid={"legs": "force", "internal_stiffness": 1e6, )"
                                   R"("position_trim_gain": 0, "attitude_trim_gain": 0})");
  const m::MapStudy st = m::parse_map_study(doc, "s.json", ".");
  REQUIRE(st.models.size() == 2);
  CHECK(st.models[0] == pronk::scene::ModelKind::kPulse);
  CHECK(st.primary_model() == pronk::scene::ModelKind::kPseudoRigid);
  // The scene's "pseudo_rigid" settings are the full model's.
  CHECK(st.base_scene.pseudo_rigid.legs == pronk::scene::PseudoRigid::Legs::kForce);
  CHECK(st.base_scene.pseudo_rigid.internal_stiffness == 1e6);
  CHECK(m::scene_at(st, 0.3, 0, st.primary_model()).model == pronk::scene::ModelKind::kPseudoRigid);
  // A robot the full model cannot build is an error of the scene, found when the study loads:
  // four dummy hips of 30 % of the body mass each leave it nothing.
  json bad = doc;
  bad["scene_overrides"].push_back(R"(/pseudo_rigid={"hips": "dummy_masses", "dummy_ratio": 0.3})");
  const std::string e = error_of(bad);
  CHECK(e.find("case3_legged_pulse.json: /pseudo_rigid: a robot the full model can build | "
               "dummy masses") != std::string::npos);
  // Not an error when no model needs the robot.
  bad["models"] = {"impulse", "pulse"};
  CHECK(error_of(bad).empty());
  // Pointer-axis values are checked for a buildable robot too (hips 0.3 m below the CoM
  // leave spring legs of length 0.25 m no room).
  json ax = doc;
  ax["scene_overrides"].back() = R"(/pseudo_rigid={"legs": "spring"})";
  ax["axes"][1] = {{"kind", "pointer"}, {"pointer", "/legs/length"}, {"values", {0.03, 0.25}}};
  CHECK(error_of(ax).find("s.json: /axes/1/values/0: a value that makes a robot the full model "
                          "can build") == 0);
}
