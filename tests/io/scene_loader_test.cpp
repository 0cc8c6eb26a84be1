// Tests of io/load/scene_loader.hpp: the shipped scenes load, the resolved scene
// round-trips exactly, every class of bad input is an io::InputError naming the
// JSON Pointer, what was expected and what was found, and --set overrides.
#include "io/load/scene_loader.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using nlohmann::json;
using pronk::io::InputError;
namespace io = pronk::io;
namespace scene = pronk::scene;

namespace {

const std::string kSceneDir = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/";
const std::vector<std::string> kShipped = {"case1_body_only.json", "case2_legged_impulse.json",
                                           "case3_legged_pulse.json"};

json shipped(const std::string& name) { return io::read_json_file(kSceneDir + name); }

/// Runs f and returns the io::InputError it throws; any other outcome fails the test.
template <class F>
InputError input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  throw std::logic_error("expected an io::InputError, none was thrown");
}

InputError parse_error(const json& doc) {
  return input_error_of([&] { io::parse_scene(doc, "bad.json"); });
}

InputError override_error(json doc, const std::string& assignment) {
  return input_error_of([&] { io::apply_override(doc, assignment); });
}

/// Checks the four parts of an error and that what() is the one-line message built from them.
void check_error(const InputError& e, const std::string& pointer, const std::string& expected,
                 const std::string& found, const std::string& file = "bad.json") {
  CHECK(e.file() == file);
  CHECK(e.pointer() == pointer);
  CHECK_THAT(e.expected(), Contains(expected));
  CHECK_THAT(e.found(), Contains(found));
  CHECK(std::string(e.what()) == file + ": " + (pointer.empty() ? "/" : pointer) + ": expected " +
                                     e.expected() + ", found " + e.found());
}

/// Field-by-field exact (bitwise for finite doubles) comparison of two scenes.
void check_same_scene(const scene::Scene& a, const scene::Scene& b) {
  CHECK(a.name == b.name);
  CHECK(a.model == b.model);
  CHECK(a.gravity == b.gravity);
  CHECK(a.attitude == b.attitude);
  CHECK(a.body.mass == b.body.mass);
  CHECK(a.body.inertia == b.body.inertia);
  CHECK(a.legs.body_only == b.legs.body_only);
  CHECK(a.legs.hips == b.legs.hips);
  CHECK(a.legs.disabled == b.legs.disabled);
  CHECK(a.legs.length == b.legs.length);
  const auto &c = a.controller, &d = b.controller;
  CHECK(c.kp == d.kp);
  CHECK(c.kd == d.kd);
  CHECK(c.hop_height == d.hop_height);
  CHECK(c.setpoint_position == d.setpoint_position);
  CHECK(c.setpoint_velocity == d.setpoint_velocity);
  CHECK(c.setpoint_yaw == d.setpoint_yaw);
  CHECK(c.bank_enabled == d.bank_enabled);
  CHECK(c.bank_kp == d.bank_kp);
  CHECK(c.bank_kd == d.bank_kd);
  CHECK(c.bank_max_roll == d.bank_max_roll);
  CHECK(c.allocation.scheme == d.allocation.scheme);
  CHECK(c.allocation.max_leg_impulse == d.allocation.max_leg_impulse);
  CHECK(c.allocation.residual_tol == d.allocation.residual_tol);
  CHECK(c.gait == d.gait);
  CHECK(c.gait_groups == d.gait_groups);
  CHECK(a.pulse.mode == b.pulse.mode);
  CHECK(a.pulse.max_force == b.pulse.max_force);
  CHECK(a.pulse.duration == b.pulse.duration);
  CHECK(a.pulse.gravity_compensation == b.pulse.gravity_compensation);
  CHECK(a.initial.position == b.initial.position);
  CHECK(a.initial.velocity == b.initial.velocity);
  CHECK(a.initial.attitude.coeffs() == b.initial.attitude.coeffs());
  CHECK(a.initial.angular_velocity == b.initial.angular_velocity);
  REQUIRE(a.disturbances.size() == b.disturbances.size());
  for (size_t i = 0; i < a.disturbances.size(); ++i) {
    CHECK(a.disturbances[i].time == b.disturbances[i].time);
    CHECK(a.disturbances[i].linear_impulse == b.disturbances[i].linear_impulse);
    CHECK(a.disturbances[i].angular_impulse == b.disturbances[i].angular_impulse);
  }
  const auto &m = a.simulation, &n = b.simulation;
  CHECK(m.duration == n.duration);
  CHECK(m.max_strides == n.max_strides);
  CHECK(m.sample_interval == n.sample_interval);
  CHECK(m.solver.method == n.solver.method);
  CHECK(m.solver.rtol == n.solver.rtol);
  CHECK(m.solver.atol == n.solver.atol);
  CHECK(m.solver.h_fixed == n.solver.h_fixed);
  CHECK(m.solver.h_max == n.solver.h_max);
  CHECK(m.solver.h_min == n.solver.h_min);
  CHECK(m.solver.h_initial == n.solver.h_initial);
  CHECK(m.solver.event_tol == n.solver.event_tol);
  CHECK(m.solver.max_steps == n.solver.max_steps);
  CHECK(m.solver.max_steps_per_second == n.solver.max_steps_per_second);
  CHECK(m.fall_min_height == n.fall_min_height);
  CHECK(m.fall_max_tilt == n.fall_max_tilt);
}

/// parse -> resolve -> parse -> resolve: both resolved documents are the same
/// text and both scenes are the same field for field.
void check_round_trip(const json& doc) {
  const scene::Scene s1 = io::parse_scene(doc, "scene.json");
  const json r1 = io::scene_to_json(s1);
  const scene::Scene s2 = io::parse_scene(r1, "scene.resolved.json");
  const json r2 = io::scene_to_json(s2);
  CHECK(r1.dump(2) == r2.dump(2));
  check_same_scene(s1, s2);
}

/// A scene that sets every optional section to a non-default value.
json rich_scene() {
  json doc = shipped("case2_legged_impulse.json");
  doc["name"] = "rich";
  doc["gravity"] = 3.71;
  doc["attitude"] = "small_angle_euler123";
  doc["body"] = {{"mass", 2.3},
                 {"inertia_tensor",
                  {{0.011, 0.0007, -0.0003}, {0.0007, 0.013, 0.0002}, {-0.0003, 0.0002, 0.019}}}};
  doc["legs"]["disabled"] = {2};
  doc["legs"]["length"] = 0.31;
  doc["controller"]["setpoint"]["yaw_deg"] = 33.3;
  doc["controller"]["bank"] = {
      {"enabled", true}, {"kp", 0.07}, {"kd", 0.11}, {"max_roll_deg", 17.3}};
  doc["controller"]["allocation"] = {
      {"scheme", "minimum_norm"}, {"max_leg_impulse", 2.5}, {"residual_tol", 1e-6}};
  doc["controller"]["gait"] = {{"kind", "alternate"}, {"groups", {{0, 3}, {1}}}};
  doc["pulse"] = {{"mode", "max_force"},
                  {"max_force", 42.5},
                  {"duration", 0.07},
                  {"gravity_compensation", false}};
  doc["initial"] = {{"position", {0.1, -0.2, 0.33}},
                    {"velocity", {0.3, 0.1, -0.2}},
                    {"attitude_deg", {7.7, -3.1, 21.9}},
                    {"euler_set", "313"},
                    {"angular_velocity", {0.5, -0.25, 1.5}}};
  doc["disturbances"] = {{{"time", 2.5}, {"linear_impulse", {0.1, 0, 0}}},
                         {{"time", 0.7}, {"angular_impulse", {0, 0.01, 0}}}};
  doc["simulation"] = {
      {"duration", 3.3},
      {"max_strides", 17},
      {"sample_interval", 0.01},
      {"solver", {{"method", "rk4"}, {"h_fixed", 2e-4}, {"h_max", 0.05}, {"event_tol", 1e-11}}},
      {"fall", {{"min_height", 0.05}, {"max_tilt_deg", 47.5}}}};
  return doc;
}

/// A temporary file removed at scope exit.
struct TempFile {
  std::string path;
  explicit TempFile(const std::string& content) {
    char tmpl[] = "/tmp/pronk_scene_XXXXXX";
    const int fd = ::mkstemp(tmpl);
    REQUIRE(fd >= 0);
    ::close(fd);
    path = tmpl;
    std::ofstream(path) << content;
  }
  ~TempFile() { std::filesystem::remove(path); }
};

}  // namespace

TEST_CASE("every shipped scene loads with the values its file states", "[io][scene]") {
  const scene::Scene c1 = io::load_scene(kSceneDir + "case1_body_only.json");
  CHECK(c1.name == "case1_body_only");
  CHECK(c1.model == scene::ModelKind::kImpulse);
  CHECK(c1.legs.body_only);
  CHECK(c1.legs.hips.empty());
  CHECK(c1.body.mass == 1.5);
  CHECK(c1.body.inertia.diagonal() == Eigen::Vector3d(0.0074, 0.0106, 0.0164));
  CHECK(c1.body.inertia(0, 1) == 0.0);
  CHECK(c1.controller.hop_height == 0.2);
  CHECK(c1.controller.setpoint_velocity == Eigen::Vector3d(0.2, 0, 0));
  CHECK(c1.initial.position == Eigen::Vector3d(0, 0.4, 0.27));
  // attitude_deg [10, 0, 0]: a 10 degree roll about body x.
  CHECK(c1.initial.attitude.w() == Approx(std::cos(5.0 * M_PI / 180.0)).epsilon(1e-15));
  CHECK(c1.initial.attitude.x() == Approx(std::sin(5.0 * M_PI / 180.0)).epsilon(1e-15));
  CHECK(c1.initial.attitude.y() == 0.0);
  CHECK(c1.initial.attitude.z() == 0.0);
  CHECK(c1.simulation.duration == 10.0);
  CHECK(c1.simulation.solver.method == pronk::ode::Method::kDopri5);
  CHECK(c1.simulation.solver.rtol == 1e-9);
  // Defaults: seed gains from the body, fall height 0.4 * leg length.
  Eigen::Matrix<double, 6, 1> kp, kd;
  kp << 1.5, 1.5, 0.0, 0.0074, 0.0106, 0.0164;
  kd << 2.25, 2.25, 1.5, 1.5 * 0.0074, 1.5 * 0.0106, 1.5 * 0.0164;
  CHECK(c1.controller.kp == kp);
  CHECK(c1.controller.kd == kd);
  CHECK(c1.simulation.fall_min_height == Approx(0.1).epsilon(1e-15));
  CHECK(c1.gravity == 9.81);

  const scene::Scene c2 = io::load_scene(kSceneDir + "case2_legged_impulse.json");
  CHECK(c2.name == "case2_legged_impulse");
  CHECK_FALSE(c2.legs.body_only);
  REQUIRE(c2.legs.hips.size() == 4);
  CHECK(c2.legs.hips[3] == Eigen::Vector3d(-0.14, -0.115, -0.04));
  CHECK(c2.legs.disabled == std::vector<bool>(4, false));
  CHECK(c2.controller.kp[3] == 0.0185);
  CHECK(c2.controller.bank_enabled);
  CHECK(c2.controller.bank_kp == 0.05);
  CHECK(c2.controller.bank_max_roll == Approx(15.0 * M_PI / 180.0).epsilon(1e-15));
  CHECK(c2.controller.allocation.scheme == pronk::control::AllocationScheme::kSeed);

  const scene::Scene c3 = io::load_scene(kSceneDir + "case3_legged_pulse.json");
  CHECK(c3.model == scene::ModelKind::kPulse);
  CHECK(c3.pulse.mode == scene::PulseMode::kDuration);
  CHECK(c3.pulse.duration == 0.1);
  CHECK(c3.pulse.gravity_compensation);
}

TEST_CASE("the resolved scene reproduces every field exactly", "[io][scene]") {
  for (const std::string& name : kShipped) {
    INFO(name);
    check_round_trip(shipped(name));
  }
  SECTION("an empty document: every default") { check_round_trip(json::object()); }
  SECTION("every optional section set to a non-default value") { check_round_trip(rich_scene()); }
  SECTION("an explicit, non-normalised attitude quaternion") {
    json doc = shipped("case1_body_only.json");
    doc["initial"].erase("attitude_deg");
    doc["initial"]["attitude_quaternion"] = {0.9, 0.1, -0.3, 0.2};
    check_round_trip(doc);
  }
}

TEST_CASE("the resolved scene states every setting explicitly", "[io][scene]") {
  const json r = io::scene_to_json(io::parse_scene(rich_scene(), "rich.json"));
  CHECK(r["name"] == "rich");
  CHECK(r["attitude"] == "small_angle_euler123");
  CHECK(r["body"]["inertia_tensor"][0][1] == 0.0007);
  CHECK(r["legs"]["kind"] == "legged");
  CHECK(r["legs"]["disabled"] == json({2}));
  CHECK(r["controller"]["gait"]["groups"] == json({{0, 3}, {1}}));
  CHECK(r["controller"]["setpoint"]["yaw_deg"].get<double>() == Approx(33.3).epsilon(1e-14));
  CHECK(r["pulse"]["mode"] == "max_force");
  CHECK(r["initial"]["attitude_quaternion"].size() == 4);
  CHECK_FALSE(r["initial"].contains("attitude_deg"));
  // Disturbances come out sorted by time.
  REQUIRE(r["disturbances"].size() == 2);
  CHECK(r["disturbances"][0]["time"] == 0.7);
  CHECK(r["disturbances"][1]["time"] == 2.5);
  CHECK(r["simulation"]["solver"]["method"] == "rk4");
  CHECK(r["simulation"]["solver"]["rtol"] == 1e-9);
  CHECK(r["simulation"]["max_strides"] == 17);
  CHECK(r["simulation"]["fall"]["min_height"] == 0.05);
  // Body-only legs carry neither hips nor disabled legs.
  const json r1 = io::scene_to_json(io::parse_scene(json::object(), "empty.json"));
  CHECK(r1["legs"] == json({{"kind", "body_only"}, {"length", 0.25}}));
  CHECK(r1["model"] == "impulse");
  CHECK(r1["disturbances"] == json::array());
}

TEST_CASE("unknown keys are rejected at every level", "[io][scene][errors]") {
  json doc = shipped("case2_legged_impulse.json");
  SECTION("top level") {
    doc["colour"] = "red";
    const InputError e = parse_error(doc);
    check_error(e, "/colour", "a known key (", "unknown key \"colour\"");
    CHECK_THAT(e.expected(), Contains("controller"));
  }
  SECTION("nested: /controller/kpp") {
    doc["controller"]["kpp"] = {1, 1, 1, 1, 1, 1};
    const InputError e = parse_error(doc);
    check_error(e, "/controller/kpp", "a known key (", "unknown key \"kpp\"");
    CHECK_THAT(e.expected(), Contains("hop_height"));
  }
  SECTION("nested twice: /simulation/solver/rtoll") {
    doc["simulation"]["solver"]["rtoll"] = 1e-6;
    check_error(parse_error(doc), "/simulation/solver/rtoll", "rtol", "unknown key \"rtoll\"");
  }
  SECTION("inside an array element: /disturbances/0/tim") {
    doc["disturbances"] = {{{"time", 1.0}, {"tim", 2.0}}};
    check_error(parse_error(doc), "/disturbances/0/tim", "time", "unknown key \"tim\"");
  }
  SECTION("nested: /pseudo_rigid/stance_attitude/kpp") {
    doc = shipped("pr_running.json");
    doc["pseudo_rigid"]["stance_attitude"] = {{"kd", {10, 1}}, {"kpp", {1, 1}}};
    check_error(parse_error(doc), "/pseudo_rigid/stance_attitude/kpp", "max_moment",
                "unknown key \"kpp\"");
  }
  SECTION("a key needing pointer escapes") {
    doc["body"]["a/b~c"] = 1;
    check_error(parse_error(doc), "/body/a~1b~0c", "a known key", "unknown key \"a/b~c\"");
  }
}

TEST_CASE("stance attitude feedback settings parse and round-trip", "[io][scene]") {
  json doc = shipped("pr_running.json");
  doc["pseudo_rigid"]["stance_attitude"] = {{"kp", {5, 2}}, {"kd", {10, 1}}, {"max_moment", 1.5}};
  const scene::Scene s = io::parse_scene(doc, "pr.json");
  CHECK(s.pseudo_rigid.stance_kp[0] == 5.0);
  CHECK(s.pseudo_rigid.stance_kp[1] == 2.0);
  CHECK(s.pseudo_rigid.stance_kd[0] == 10.0);
  CHECK(s.pseudo_rigid.stance_kd[1] == 1.0);
  CHECK(s.pseudo_rigid.stance_max_moment == 1.5);
  CHECK(s.pseudo_rigid.stance_feedback());
  const json r = io::scene_to_json(s)["pseudo_rigid"]["stance_attitude"];
  CHECK(r["kd"] == json({10.0, 1.0}));
  CHECK(r["max_moment"] == 1.5);
  doc["pseudo_rigid"]["stance_attitude"] = {{"kd", {-1, 1}}};
  CHECK_THROWS_AS(io::parse_scene(doc, "pr.json"), InputError);
  doc["pseudo_rigid"]["stance_attitude"] = json::object();  // given, but no gains: off
  CHECK_FALSE(io::parse_scene(doc, "pr.json").pseudo_rigid.stance_feedback());
  doc["pseudo_rigid"].erase("stance_attitude");  // left out: the robot-scaled default, on
  CHECK(io::parse_scene(doc, "pr.json").pseudo_rigid.stance_feedback());
}

TEST_CASE("level feet setting parses, round-trips and names its pointer", "[io][scene]") {
  json doc = shipped("pr_running.json");
  CHECK(io::parse_scene(doc, "pr.json").pseudo_rigid.level_feet);  // on in the shipped scene
  doc["pseudo_rigid"]["level_feet"] = false;
  const scene::Scene s = io::parse_scene(doc, "pr.json");
  CHECK_FALSE(s.pseudo_rigid.level_feet);
  CHECK(io::scene_to_json(s)["pseudo_rigid"]["level_feet"] == false);
  doc["pseudo_rigid"].erase("level_feet");
  CHECK(io::parse_scene(doc, "pr.json").pseudo_rigid.level_feet);  // default on (running)
  doc["pseudo_rigid"]["level_feet"] = 1;
  check_error(parse_error(doc), "/pseudo_rigid/level_feet", "true or false", "number 1");
}

TEST_CASE("values of the wrong type are rejected", "[io][scene][errors]") {
  json doc = shipped("case1_body_only.json");
  SECTION("string for a number") {
    doc["body"]["mass"] = "heavy";
    check_error(parse_error(doc), "/body/mass", "a finite number in [1e-06, 1000000]",
                "string \"heavy\"");
  }
  SECTION("string for a bounded number") {
    doc["gravity"] = "9.81";
    check_error(parse_error(doc), "/gravity", "a finite number in [0, 1000]", "string \"9.81\"");
  }
  SECTION("number for a vector") {
    doc["initial"]["position"] = 0.3;
    check_error(parse_error(doc), "/initial/position", "an array of 3 numbers", "number 0.3");
  }
  SECTION("vector of the wrong length") {
    doc["initial"]["velocity"] = {1, 2};
    check_error(parse_error(doc), "/initial/velocity", "an array of 3 numbers",
                "array of 2 element(s) [1,2]");
  }
  SECTION("string inside a vector") {
    doc["initial"]["position"][1] = "a";
    check_error(parse_error(doc), "/initial/position/1", "a finite number", "string \"a\"");
  }
  SECTION("number for an object") {
    doc["controller"] = 3;
    check_error(parse_error(doc), "/controller", "an object", "number 3");
  }
  SECTION("boolean for a string choice") {
    doc["model"] = true;
    check_error(parse_error(doc), "/model", "one of \"impulse\" \"pulse\"", "boolean true");
  }
  SECTION("unknown choice") {
    doc["simulation"]["solver"]["method"] = "rk45";
    check_error(parse_error(doc), "/simulation/solver/method", "\"dopri5\"", "string \"rk45\"");
  }
  SECTION("number for a boolean") {
    doc["controller"]["bank"] = {{"enabled", 1}};
    check_error(parse_error(doc), "/controller/bank/enabled", "true or false", "number 1");
  }
  SECTION("fractional integer") {
    doc["simulation"]["max_strides"] = 2.5;
    check_error(parse_error(doc), "/simulation/max_strides", "an integer in [1, 1000000000]",
                "number 2.5");
  }
  SECTION("a document that is not an object") {
    check_error(parse_error(json::array({1, 2})), "", "an object", "array of 2 element(s)");
  }
}

TEST_CASE("values out of range are rejected", "[io][scene][errors]") {
  json doc = shipped("case2_legged_impulse.json");
  SECTION("negative mass") {
    doc["body"]["mass"] = -1;
    check_error(parse_error(doc), "/body/mass", "a finite number in [1e-06, 1000000]", "number -1");
  }
  SECTION("hop height 0") {
    doc["controller"]["hop_height"] = 0;
    check_error(parse_error(doc), "/controller/hop_height", "a finite number > 0", "number 0");
  }
  SECTION("rtol -1") {
    doc["simulation"]["solver"]["rtol"] = -1;
    check_error(parse_error(doc), "/simulation/solver/rtol", "a finite number > 0", "number -1");
  }
  SECTION("max_roll_deg 100") {
    doc["controller"]["bank"]["max_roll_deg"] = 100;
    check_error(parse_error(doc), "/controller/bank/max_roll_deg", "a finite number in [1e-06, 89]",
                "number 100");
  }
  SECTION("negative gain element") {
    doc["controller"]["kd"][4] = -0.5;
    check_error(parse_error(doc), "/controller/kd/4", "a finite number in [0, 1000000000]",
                "number -0.5");
  }
  SECTION("hop-height feedback bounds") {
    doc["pseudo_rigid"]["hop_trim_max"] = 11;
    check_error(parse_error(doc), "/pseudo_rigid/hop_trim_max", "a finite number in [0, 10]",
                "number 11");
    doc["pseudo_rigid"]["hop_trim_max"] = 3;
    doc["pseudo_rigid"]["hop_trim_gain"] = -0.1;
    check_error(parse_error(doc), "/pseudo_rigid/hop_trim_gain", "a finite number in [0, 2]",
                "number -0.1");
  }
  SECTION("thrust law and integral position action") {
    doc["pseudo_rigid"]["thrust"] = "spring";
    const std::string e = parse_error(doc).what();
    CHECK(e.find("/pseudo_rigid/thrust") != std::string::npos);
    CHECK(e.find("impulse") != std::string::npos);
    CHECK(e.find("energy") != std::string::npos);
    CHECK(e.find("spring") != std::string::npos);
    doc["pseudo_rigid"]["thrust"] = "energy";
    doc["pseudo_rigid"]["position_trim_gain"] = 3;
    check_error(parse_error(doc), "/pseudo_rigid/position_trim_gain", "a finite number in [0, 2]",
                "number 3");
    doc["pseudo_rigid"]["position_trim_gain"] = 0.3;
    doc["pseudo_rigid"]["attitude_trim_gain"] = -1;
    check_error(parse_error(doc), "/pseudo_rigid/attitude_trim_gain", "a finite number in [0, 2]",
                "number -1");
    doc["pseudo_rigid"]["attitude_trim_gain"] = 1;
    doc["pseudo_rigid"]["attitude_trim_max"] = 1.5;
    check_error(parse_error(doc), "/pseudo_rigid/attitude_trim_max", "a finite number in [0, 1]",
                "number 1.5");
  }
  SECTION("max_strides 0") {
    doc["simulation"]["max_strides"] = 0;
    check_error(parse_error(doc), "/simulation/max_strides", "an integer in [1, 1000000000]",
                "number 0");
  }
  SECTION("negative crawl guard") {
    doc["simulation"]["solver"]["max_steps_per_second"] = -1;
    check_error(parse_error(doc), "/simulation/solver/max_steps_per_second",
                "a finite number in [0, 1e+15]", "number -1");
  }
  SECTION("h_min not below h_max") {
    doc["simulation"]["solver"]["h_min"] = 0.5;
    doc["simulation"]["solver"]["h_max"] = 0.1;
    check_error(parse_error(doc), "/simulation/solver/h_min", "valid solver options",
                "must be < h_max");
  }
  SECTION("a name that is not a plain directory name") {
    doc["name"] = "";
    check_error(parse_error(doc), "/name", "a name usable as a directory name", "an empty name");
    doc["name"] = "a/b";
    check_error(parse_error(doc), "/name", "a name usable as a directory name", "\"a/b\"");
    doc["name"] = "..";
    check_error(parse_error(doc), "/name", "a name usable as a directory name", "\"..\"");
  }
}

TEST_CASE("inertia must be a physical body", "[io][scene][errors]") {
  json doc = shipped("case1_body_only.json");
  SECTION("principal moments violating the triangle inequality") {
    doc["body"]["inertia"] = {0.1, 0.1, 0.3};
    check_error(parse_error(doc), "/body/inertia", "triangle inequalities",
                "Izz = 0.3 > 0.2 (sum of the other two)");
  }
  SECTION("the first moment violating it") {
    doc["body"]["inertia"] = {0.5, 0.1, 0.3};
    check_error(parse_error(doc), "/body/inertia", "triangle inequalities", "Ixx = 0.5 > 0.4");
  }
  SECTION("a full tensor violating it") {
    doc["body"].erase("inertia");
    doc["body"]["inertia_tensor"] = {{0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.3}};
    check_error(parse_error(doc), "/body/inertia_tensor", "triangle inequalities", "0.3 > 0.2");
  }
  SECTION("a non-positive moment") {
    doc["body"]["inertia"] = {0.01, 0.0, 0.01};
    check_error(parse_error(doc), "/body/inertia", "positive principal moments", "moment 0 kg m^2");
  }
  SECTION("an asymmetric tensor") {
    doc["body"].erase("inertia");
    doc["body"]["inertia_tensor"] = {{0.01, 0.001, 0}, {0, 0.01, 0}, {0, 0, 0.015}};
    check_error(parse_error(doc), "/body/inertia_tensor", "a symmetric 3x3 matrix",
                "an asymmetric matrix");
  }
  SECTION("an indefinite symmetric tensor") {
    doc["body"].erase("inertia");
    doc["body"]["inertia_tensor"] = {{0.01, 0.02, 0}, {0.02, 0.01, 0}, {0, 0, 0.015}};
    check_error(parse_error(doc), "/body/inertia_tensor", "positive principal moments", "moment -");
  }
  SECTION("a tensor row of the wrong length") {
    doc["body"].erase("inertia");
    doc["body"]["inertia_tensor"] = {{0.01, 0, 0}, {0, 0.01}, {0, 0, 0.015}};
    check_error(parse_error(doc), "/body/inertia_tensor/1", "an array of 3 numbers",
                "array of 2 element(s)");
  }
  SECTION("both inertia and inertia_tensor") {
    doc["body"]["inertia_tensor"] = {{0.01, 0, 0}, {0, 0.01, 0}, {0, 0, 0.015}};
    check_error(parse_error(doc), "/body/inertia_tensor",
                "either \"inertia\" or \"inertia_tensor\"", "both keys");
  }
  SECTION("a valid rotated tensor is accepted and kept") {
    doc["body"].erase("inertia");
    doc["body"]["inertia_tensor"] = {{0.01, 0.002, 0}, {0.002, 0.012, 0}, {0, 0, 0.02}};
    const scene::Scene s = io::parse_scene(doc, "ok.json");
    CHECK(s.body.inertia(0, 1) == 0.002);
    CHECK(s.body.inertia(1, 0) == 0.002);
    CHECK(s.body.inertia(2, 2) == 0.02);
  }
}

TEST_CASE("legs, gait groups and the initial state are checked", "[io][scene][errors]") {
  json doc = shipped("case2_legged_impulse.json");
  SECTION("legged without hips") {
    doc["legs"].erase("hips");
    check_error(parse_error(doc), "/legs/hips", "an array of hip positions (legged)", "nothing");
  }
  SECTION("body_only with hips") {
    doc["legs"]["kind"] = "body_only";
    check_error(parse_error(doc), "/legs/hips", "no hips for kind \"body_only\"", "hips");
  }
  SECTION("a hip that is not a point") {
    doc["legs"]["hips"][2] = {0.1, 0.1};
    check_error(parse_error(doc), "/legs/hips/2", "an array of 3 numbers", "array of 2 element(s)");
  }
  SECTION("disabled leg index out of range") {
    doc["legs"]["disabled"] = {1, 4};
    check_error(parse_error(doc), "/legs/disabled/1", "integers in [0, 3]", "number 4");
  }
  SECTION("disabled leg index negative") {
    doc["legs"]["disabled"] = {-1};
    check_error(parse_error(doc), "/legs/disabled/0", "integers in [0, 3]", "number -1");
  }
  SECTION("disabled legs of a body-only robot (which has none)") {
    json c1 = shipped("case1_body_only.json");
    c1["legs"]["disabled"] = {0};
    check_error(parse_error(c1), "/legs/disabled/0", "no disabled legs", "number 0");
    c1["legs"]["disabled"] = json::array();
    CHECK(io::parse_scene(c1, "ok.json").legs.disabled.empty());
  }
  SECTION("valid disabled legs are applied") {
    doc["legs"]["disabled"] = {3, 1};
    CHECK(io::parse_scene(doc, "ok.json").legs.disabled ==
          std::vector<bool>{false, true, false, true});
  }
  SECTION("gait group with an index past the last leg") {
    doc["controller"]["gait"] = {{"kind", "alternate"}, {"groups", {{0, 3}, {1, 4}}}};
    check_error(parse_error(doc), "/controller/gait/groups/1/1", "a distinct leg index in [0, 3]",
                "number 4");
  }
  SECTION("gait group with a repeated index") {
    doc["controller"]["gait"] = {{"kind", "alternate"}, {"groups", {{0, 0}, {1, 2}}}};
    check_error(parse_error(doc), "/controller/gait/groups/0/1", "a distinct leg index",
                "number 0");
  }
  SECTION("gait group that is empty") {
    doc["controller"]["gait"] = {{"kind", "alternate"}, {"groups", {json::array(), {1, 2}}}};
    check_error(parse_error(doc), "/controller/gait/groups/0", "non-empty arrays of leg indices",
                "array of 0 element(s)");
  }
  SECTION("alternating gait without groups") {
    doc["controller"]["gait"] = {{"kind", "alternate"}};
    check_error(parse_error(doc), "/controller/gait/groups", "leg index groups", "nothing");
  }
  SECTION("alternating gait of a body-only robot") {
    json c1 = shipped("case1_body_only.json");
    c1["controller"]["gait"] = {{"kind", "alternate"}, {"groups", {{0}}}};
    check_error(parse_error(c1), "/controller/gait/kind", "a legged robot", "body_only legs");
  }
  SECTION("initial CoM below the fall height") {
    doc["initial"]["position"][2] = 0.05;
    check_error(parse_error(doc), "/initial/position/2", "a CoM height above the fall height 0.1 m",
                "0.05");
  }
  SECTION("initial CoM exactly at an explicit fall height") {
    doc["simulation"]["fall"] = {{"min_height", 0.27}};
    check_error(parse_error(doc), "/initial/position/2",
                "a CoM height above the fall height 0.27 m", "0.27");
  }
  SECTION("both attitude_deg and attitude_quaternion") {
    doc["initial"]["attitude_quaternion"] = {1, 0, 0, 0};
    check_error(parse_error(doc), "/initial/attitude_quaternion",
                "either attitude_deg or attitude_quaternion", "both");
  }
  SECTION("a zero quaternion") {
    doc["initial"].erase("attitude_deg");
    doc["initial"]["attitude_quaternion"] = {0, 0, 0, 0};
    check_error(parse_error(doc), "/initial/attitude_quaternion", "a non-zero quaternion", "zero");
  }
  SECTION("a disturbance without its time") {
    doc["disturbances"] = {{{"linear_impulse", {0.1, 0, 0}}}};
    check_error(parse_error(doc), "/disturbances/0/time", "a value (required key)", "nothing");
  }
}

TEST_CASE("non-finite and overflowing numbers are rejected", "[io][scene][errors]") {
  const double inf = std::numeric_limits<double>::infinity();
  json doc = shipped("case1_body_only.json");
  SECTION("infinite mass (a document built in memory)") {
    doc["body"]["mass"] = inf;
    check_error(parse_error(doc), "/body/mass", "a finite number in [1e-06, 1000000]", "number");
  }
  SECTION("minus infinity in a vector") {
    doc["initial"]["velocity"] = {0, -inf, 0};
    check_error(parse_error(doc), "/initial/velocity/1", "a finite number", "number");
  }
  SECTION("NaN in a bounded number") {
    doc["gravity"] = std::nan("");
    check_error(parse_error(doc), "/gravity", "a finite number in [0, 1000]", "number");
  }
  SECTION("infinity in an inertia tensor") {
    doc["body"].erase("inertia");
    doc["body"]["inertia_tensor"] = {{0.01, 0, 0}, {0, inf, 0}, {0, 0, 0.015}};
    check_error(parse_error(doc), "/body/inertia_tensor/1/1", "a finite number", "number");
  }
  SECTION("1e400 in a scene file is bad input, not a crash or infinity") {
    const TempFile f(R"({"name": "huge", "body": {"mass": 1e400}})");
    const InputError e = input_error_of([&] { io::load_scene(f.path); });
    CHECK(e.file() == f.path);
    CHECK_THAT(e.expected(), Contains("finite number"));
    CHECK_THAT(e.found(), Contains("1e400"));
  }
  SECTION("1e400 in an override is bad input") {
    const InputError e = override_error(doc, "/body/mass=1e400");
    CHECK_THAT(e.file(), Contains("--set /body/mass=1e400"));
    CHECK(e.pointer() == "/body/mass");
    CHECK_THAT(e.expected(), Contains("finite number"));
    CHECK_THAT(e.found(), Contains("1e400"));
  }
}

TEST_CASE("read_json_file reports missing files and syntax errors", "[io][scene][errors]") {
  SECTION("missing file") {
    const InputError e = input_error_of([] { io::read_json_file("/nonexistent/dir/s.json"); });
    CHECK(e.file() == "/nonexistent/dir/s.json");
    CHECK(e.pointer().empty());
    CHECK(e.expected() == "a readable JSON file");
    CHECK(e.found() == "no such file or unreadable");
  }
  SECTION("syntax error") {
    const TempFile f("{\"body\": {\"mass\": }}");
    const InputError e = input_error_of([&] { io::read_json_file(f.path); });
    CHECK(e.file() == f.path);
    CHECK(e.expected() == "valid JSON");
    CHECK_THAT(e.found(), StartsWith("a syntax error") && Contains("line 1"));
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }
  SECTION("a good file") {
    const TempFile f(R"({"name": "x", "gravity": 1.62})");
    CHECK(io::read_json_file(f.path) == json({{"name", "x"}, {"gravity", 1.62}}));
    CHECK(io::load_scene(f.path, {"/gravity=3.71"}).gravity == 3.71);
  }
}

TEST_CASE("apply_override sets values", "[io][override]") {
  json doc = shipped("case1_body_only.json");
  SECTION("a nested number") {
    io::apply_override(doc, "/controller/hop_height=0.3");
    CHECK(doc["controller"]["hop_height"] == 0.3);
    CHECK(io::parse_scene(doc, "s.json").controller.hop_height == 0.3);
  }
  SECTION("an array element, leaving the others") {
    io::apply_override(doc, "/initial/position/1=0.1");
    CHECK(doc["initial"]["position"] == json({0, 0.1, 0.27}));
    CHECK(io::parse_scene(doc, "s.json").initial.position == Eigen::Vector3d(0, 0.1, 0.27));
  }
  SECTION("a bare word is a string") {
    io::apply_override(doc, "/model=pulse");
    CHECK(doc["model"] == "pulse");
    CHECK(io::parse_scene(doc, "s.json").model == scene::ModelKind::kPulse);
  }
  SECTION("a quoted JSON string") {
    io::apply_override(doc, "/name=\"renamed\"");
    CHECK(doc["name"] == "renamed");
  }
  SECTION("a JSON array and a JSON boolean") {
    io::apply_override(doc, "/initial/angular_velocity=[1.5,0,-2]");
    CHECK(doc["initial"]["angular_velocity"] == json({1.5, 0, -2}));
    io::apply_override(doc, "/controller/bank={\"enabled\":true}");
    CHECK(doc["controller"]["bank"]["enabled"] == true);
  }
  SECTION("a missing leaf in an existing object is created") {
    REQUIRE_FALSE(doc["simulation"].contains("max_strides"));
    io::apply_override(doc, "/simulation/max_strides=5");
    CHECK(doc["simulation"]["max_strides"] == 5);
    CHECK(io::parse_scene(doc, "s.json").simulation.max_strides == 5);
  }
  SECTION("the value may contain '='") {
    io::apply_override(doc, "/name=a=b");
    CHECK(doc["name"] == "a=b");
  }
  SECTION("later overrides win") {
    io::apply_override(doc, "/gravity=1");
    io::apply_override(doc, "/gravity=2");
    CHECK(doc["gravity"] == 2);
  }
}

TEST_CASE("apply_override rejects bad assignments", "[io][override][errors]") {
  const json doc = shipped("case1_body_only.json");
  SECTION("missing parent") {
    check_error(override_error(doc, "/nope/x=1"), "/nope/x",
                "a pointer whose parent exists in the scene", "no value at /nope",
                "command line (--set /nope/x=1)");
  }
  SECTION("missing parent inside an existing object") {
    check_error(override_error(doc, "/initial/angular_velocity/0=40"),
                "/initial/angular_velocity/0", "a pointer whose parent exists",
                "no value at /initial/angular_velocity",
                "command line (--set /initial/angular_velocity/0=40)");
  }
  SECTION("array index past the end") {
    check_error(override_error(doc, "/initial/position/3=1"), "/initial/position/3",
                "an index below 3", "\"3\"", "command line (--set /initial/position/3=1)");
  }
  SECTION("array index that is not a number") {
    check_error(override_error(doc, "/initial/position/-=1"), "/initial/position/-",
                "an index below 3", "\"-\"", "command line (--set /initial/position/-=1)");
    check_error(override_error(doc, "/initial/position/y=1"), "/initial/position/y",
                "an index below 3", "\"y\"", "command line (--set /initial/position/y=1)");
  }
  SECTION("an array index too large for any array, inside the pointer") {
    const std::string a = "/initial/position/99999999999999999999999/x=1";
    const InputError e = override_error(doc, a);
    CHECK(e.file() == "command line (--set " + a + ")");
    CHECK(e.pointer() == "/initial/position/99999999999999999999999/x");
  }
  SECTION("parent is a number") {
    check_error(override_error(doc, "/body/mass/x=1"), "/body/mass/x",
                "an object or array at the parent", "number 1.5",
                "command line (--set /body/mass/x=1)");
  }
  SECTION("missing '='") {
    check_error(override_error(doc, "/body/mass"), "", "--set /json/pointer=value",
                "\"/body/mass\"", "command line");
  }
  SECTION("missing leading '/'") {
    check_error(override_error(doc, "body/mass=2"), "", "--set /json/pointer=value",
                "\"body/mass=2\"", "command line");
  }
  SECTION("empty assignment") {
    check_error(override_error(doc, ""), "", "--set /json/pointer=value", "\"\"", "command line");
  }
  SECTION("an invalid pointer escape") {
    const InputError e = override_error(doc, "/body/m~2=1");
    CHECK(e.file() == "command line (--set /body/m~2=1)");
    CHECK(e.pointer() == "/body/m~2");
    CHECK(e.expected() == "a valid JSON Pointer");
  }
  SECTION("an override that parses but is out of range is caught by parse_scene") {
    json d = doc;
    io::apply_override(d, "/body/mass=-1");
    check_error(parse_error(d), "/body/mass", "a finite number in [1e-06, 1000000]", "number -1");
  }
}

TEST_CASE("pulse_aware_hop needs a known stance duration", "[io][scene]") {
  nlohmann::json doc = pronk::io::read_json_file(std::string(PRONK_SOURCE_DIR) +
                                                 "/studies/scenes/legged_pulse_duty50.json");
  REQUIRE(pronk::io::parse_scene(doc, "duty50.json").controller.pulse_aware_hop);
  doc["pulse"]["mode"] = "max_force";
  try {
    pronk::io::parse_scene(doc, "duty50.json");
    FAIL("max_force with the pulse-aware hop law was accepted");
  } catch (const pronk::io::InputError& e) {
    CHECK(e.pointer() == "/controller/pulse_aware_hop");
    CHECK(e.file() == "duty50.json");
  }
  // The impulse model ignores the law: accepted.
  doc["model"] = "impulse";
  CHECK(pronk::io::parse_scene(doc, "duty50.json").controller.pulse_aware_hop);
  doc["controller"]["pulse_aware_hop"] = "yes";
  CHECK_THROWS_AS(pronk::io::parse_scene(doc, "duty50.json"), pronk::io::InputError);
}

TEST_CASE("verlet's event restart is read, written back only when not the default, and checked",
          "[io][scene]") {
  json doc = io::read_json_file(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json");
  const scene::Scene plain = io::parse_scene(doc, "scene.json");
  CHECK(plain.pseudo_rigid.solver.event_restart == pronk::ode::EventRestart::kInterpolant);
  // Absent at its default: the scenes recorded before the setting existed keep their hash.
  CHECK_FALSE(io::scene_to_json(plain)["pseudo_rigid"]["solver"].contains("event_restart"));
  doc["pseudo_rigid"]["solver"] = {{"event_restart", "step"}};
  const scene::Scene step = io::parse_scene(doc, "scene.json");
  CHECK(step.pseudo_rigid.solver.event_restart == pronk::ode::EventRestart::kStep);
  CHECK(io::scene_to_json(step)["pseudo_rigid"]["solver"]["event_restart"] == "step");
  check_round_trip(doc);
  doc["pseudo_rigid"]["solver"]["event_restart"] = "midpoint";
  check_error(parse_error(doc), "/pseudo_rigid/solver/event_restart",
              "one of \"interpolant\" \"step\"", "string \"midpoint\"");
}

TEST_CASE("verlet's flight step is read, written back only when set, and checked", "[io][scene]") {
  json doc = io::read_json_file(std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json");
  const scene::Scene plain = io::parse_scene(doc, "scene.json");
  CHECK(plain.pseudo_rigid.solver.h_flight == 0.0);
  // Absent at its default: the scenes recorded before the setting existed keep their hash.
  CHECK_FALSE(io::scene_to_json(plain)["pseudo_rigid"]["solver"].contains("h_flight"));
  doc["pseudo_rigid"]["feet"] = "quasi_static";
  doc["pseudo_rigid"]["solver"] = {{"method", "verlet"}, {"h_fixed", 2.6e-4}, {"h_flight", 5e-3}};
  const scene::Scene set = io::parse_scene(doc, "scene.json");
  CHECK(set.pseudo_rigid.solver.h_flight == 5e-3);
  CHECK(io::scene_to_json(set)["pseudo_rigid"]["solver"]["h_flight"] == 5e-3);
  check_round_trip(doc);
  doc["pseudo_rigid"]["solver"]["h_flight"] = -1e-3;
  check_error(parse_error(doc), "/pseudo_rigid/solver/h_flight", "a finite number in [0, 1]",
              "number -0.001");
  // Auto chooses it.
  doc["pseudo_rigid"]["solver"] = {{"method", "auto"}, {"h_flight", 5e-3}};
  check_error(parse_error(doc), "/pseudo_rigid/solver/h_flight", "no h_flight under",
              "number 0.005");
}
