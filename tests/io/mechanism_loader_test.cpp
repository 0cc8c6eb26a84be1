// Mechanism scene loader: every shipped mechanism loads; each class of bad
// input is an InputError with the exact JSON Pointer; "auto" stiffness is
// resolved to numbers that reload to the same mechanism.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"

using nlohmann::json;
namespace pr = pronk::pseudorigid;
namespace io = pronk::io;

namespace {

const std::string kDir = std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/";

json base() {
  return json::parse(R"({
    "kind": "mechanism", "name": "t",
    "masses": [{"name": "a", "mass": 1, "position": [0, 0, 1]}],
    "anchors": [{"name": "p", "position": [0, 0, 2]}],
    "bodies": [{"name": "b", "mass": 2, "inertia": [1, 1, 0.5], "com": [1, 0, 1],
                "ghost_points": [{"name": "hip", "position": [0.1, 0, 0]}]}],
    "connections": [{"name": "s", "a": "a", "b": "p", "stiffness": 100, "rest_length": "initial"}],
    "surfaces": [{"name": "g", "type": "plane", "nodes": ["a", "b.0"], "friction": 0.8}],
    "forces": [{"name": "f", "frame": "body", "node": "hip", "body": "b", "force": [0, 0, 1],
                "t_start": 0.1, "t_end": 0.2}],
    "simulation": {"t_end": 0.1}
  })");
}

/// Pointer of the InputError thrown for `doc` ("<none>" when it loads).
std::string error_pointer(const json& doc) {
  try {
    io::parse_mechanism(doc, "x.json");
  } catch (const io::InputError& e) {
    return e.pointer();
  }
  return "<none>";
}

}  // namespace

TEST_CASE("every shipped mechanism scene loads", "[io][mechanism]") {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kDir)) {
    if (entry.path().extension() != ".json") continue;
    const json doc = io::read_json_file(entry.path().string());
    REQUIRE(io::is_mechanism_document(doc));
    const io::LoadedMechanism lm = io::parse_mechanism(doc, entry.path().string());
    CHECK(lm.mechanism.dimension() > 0);
    // The resolved document reloads to the same mechanism.
    const io::LoadedMechanism again = io::parse_mechanism(lm.resolved, "resolved");
    CHECK(again.mechanism.dimension() == lm.mechanism.dimension());
    CHECK(again.resolved == lm.resolved);
    ++n;
  }
  CHECK(n >= 4);
}

TEST_CASE("a valid mechanism document builds the expected components", "[io][mechanism]") {
  const io::LoadedMechanism lm = io::parse_mechanism(base(), "x.json");
  const pr::Mechanism& m = lm.mechanism;
  CHECK(m.masses.size() == 5);  // one free mass + four body masses
  CHECK(m.bodies.size() == 1);
  CHECK(m.ghost_points.size() == 1);
  CHECK(m.connections.size() == 1 + 6);  // plus six internal springs
  CHECK(m.connections[6].rest_length == Approx(1.0).epsilon(1e-15));
  REQUIRE(m.surfaces.size() == 1);
  CHECK(m.surfaces[0].nodes.size() == 2);
  CHECK(m.surfaces[0].stiffness == 1e5);
  CHECK(m.surfaces[0].friction == 0.8);
  CHECK(m.surfaces[0].slip_velocity == 1e-3);
  REQUIRE(m.body_forces.size() == 1);
  CHECK(m.body_forces[0].t_end == 0.2);
  // No method named: "auto", the default, chooses it (method_choice.hpp) and the resolved
  // scene holds the choice as numbers.
  REQUIRE(lm.method_auto);
  CHECK(m.simulation.solver.method == lm.method_choice.method);
  CHECK(lm.resolved["simulation"]["method"] ==
        std::string(pronk::ode::to_string(lm.method_choice.method)));
  CHECK(m.simulation.solver.max_steps_per_second == 1e6);
  CHECK(lm.resolved["simulation"]["max_steps_per_second"] == 1e6);
  // A named method keeps its settings; verlet's energy budget is off by default.
  json named = base();
  named["simulation"]["method"] = "rodas4";
  const io::LoadedMechanism ln = io::parse_mechanism(named, "x.json");
  CHECK_FALSE(ln.method_auto);
  CHECK(ln.mechanism.simulation.solver.method == pronk::ode::Method::kRodas4);
  CHECK(ln.mechanism.simulation.energy_tol == 0.0);
  CHECK(ln.resolved["simulation"]["energy_tol"] == 0.0);
  // Full tensor equal to the principal one gives the same mass placement.
  json full = base();
  full["bodies"][0]["inertia"] = json::parse("[[1,0,0],[0,1,0],[0,0,0.5]]");
  const io::LoadedMechanism lf = io::parse_mechanism(full, "x.json");
  for (int i = 0; i < 4; ++i) {
    CHECK((lf.mechanism.bodies[0].local[i] - m.bodies[0].local[i]).norm() < 1e-12);
  }
}

TEST_CASE("auto stiffness is chosen from the budgets and resolved to numbers", "[io][mechanism]") {
  json doc = base();
  doc["simulation"]["internal_stiffness"] = "auto";
  doc["simulation"]["contact_stiffness"] = "auto";
  doc["simulation"]["penetration_budget"] = 1e-3;
  const io::LoadedMechanism lm = io::parse_mechanism(doc, "x.json");
  REQUIRE(lm.contact_auto);
  // contact k = load_factor * M g / budget = 10 * 3 kg * 9.81 / 1e-3
  CHECK(lm.stiffness.contact == Approx(10 * 3.0 * 9.81 / 1e-3).epsilon(1e-12));
  CHECK(lm.mechanism.surfaces[0].stiffness == lm.stiffness.contact);
  CHECK(lm.stiffness.internal_max > 0);
  CHECK(lm.resolved["simulation"]["contact_stiffness"].is_number());
  const io::LoadedMechanism again = io::parse_mechanism(lm.resolved, "r.json");
  CHECK(again.mechanism.surfaces[0].stiffness == lm.stiffness.contact);
  CHECK(again.mechanism.connections[1].stiffness == lm.mechanism.connections[1].stiffness);
}

TEST_CASE("bad mechanism input names the exact JSON Pointer", "[io][mechanism]") {
  struct Case {
    const char* what;
    const char* ptr;       // where to change the document
    const char* value;     // new value (JSON); "DELETE" removes the key
    const char* expected;  // pointer of the error
  };
  const Case cases[] = {
      {"unknown top-level key", "/masss", "[]", "/masss"},
      {"unknown key in a mass", "/masses/0/velocty", "[0,0,0]", "/masses/0/velocty"},
      {"unknown simulation key", "/simulation/rtoll", "1e-6", "/simulation/rtoll"},
      {"negative mass", "/masses/0/mass", "-1", "/masses/0/mass"},
      {"position of wrong length", "/masses/0/position", "[0,0]", "/masses/0/position"},
      {"non-number position", "/masses/0/position", "[0,\"x\",0]", "/masses/0/position/1"},
      {"duplicate node name", "/anchors/0/name", "\"a\"", "/anchors/0/name"},
      {"unknown node in a connection", "/connections/0/b", "\"nope\"", "/connections/0/b"},
      {"connection to itself", "/connections/0/b", "\"a\"", "/connections/0/b"},
      {"bad rest length word", "/connections/0/rest_length", "\"init\"",
       "/connections/0/rest_length"},
      {"triangle-violating inertia", "/bodies/0/inertia", "[1, 1, 3]", "/bodies/0/inertia"},
      {"non-symmetric tensor", "/bodies/0/inertia", "[[1,0.1,0],[0,1,0],[0,0,1]]",
       "/bodies/0/inertia"},
      {"bad Euler set", "/bodies/0/attitude_set", "\"321\"", "/bodies/0/attitude_set"},
      {"unknown surface type", "/surfaces/0/type", "\"sphere\"", "/surfaces/0/type"},
      {"unknown surface node", "/surfaces/0/nodes/1", "\"b.7\"", "/surfaces/0/nodes/1"},
      {"zero surface direction", "/surfaces/0/direction", "[0,0,0]", "/surfaces/0/direction"},
      {"negative friction", "/surfaces/0/friction", "-0.5", "/surfaces/0/friction"},
      {"friction on a line", "/surfaces/0/type", "\"line\"", "/surfaces/0/friction"},
      {"zero slip velocity", "/surfaces/0/slip_velocity", "0", "/surfaces/0/slip_velocity"},
      {"unknown body of a force", "/forces/0/body", "\"c\"", "/forces/0/body"},
      {"force window ends before it starts", "/forces/0/t_end", "0.05", "/forces/0/t_end"},
      {"unknown method", "/simulation/method", "\"rk45\"", "/simulation/method"},
      {"bad error norm", "/simulation/error_norm", "\"max\"", "/simulation/error_norm"},
      {"negative crawl guard", "/simulation/max_steps_per_second", "-1",
       "/simulation/max_steps_per_second"},
      {"negative energy tolerance", "/simulation/energy_tol", "-1e-4", "/simulation/energy_tol"},
      {"energy tolerance above 0.5", "/simulation/energy_tol", "0.9", "/simulation/energy_tol"},
      {"stiffness word other than auto", "/simulation/internal_stiffness", "\"stiff\"",
       "/simulation/internal_stiffness"},
      {"stiffness of wrong type", "/simulation/contact_stiffness", "true",
       "/simulation/contact_stiffness"},
      {"negative t_end", "/simulation/t_end", "-1", "/simulation/t_end"},
      {"absurd t_end", "/simulation/t_end", "1e308", "/simulation/t_end"},
      {"too many output samples", "/simulation/output_interval", "1e-9",
       "/simulation/output_interval"},
      {"check_jacobian not boolean", "/simulation/check_jacobian", "1",
       "/simulation/check_jacobian"},
      {"wrong kind", "/kind", "\"robot\"", "/kind"},
      {"missing inertia", "/bodies/0/inertia", "DELETE", "/bodies/0/inertia"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    json doc = base();
    const json::json_pointer p(c.ptr);
    if (std::string(c.value) == "DELETE") {
      doc[p.parent_pointer()].erase(p.back());
    } else {
      doc[p] = json::parse(c.value);
    }
    CHECK(error_pointer(doc) == c.expected);
  }
  // Per-surface stiffness while contact stiffness is automatic is contradictory.
  json doc = base();
  doc["simulation"]["contact_stiffness"] = "auto";
  doc["surfaces"][0]["stiffness"] = 1e4;
  CHECK(error_pointer(doc) == "/surfaces/0/stiffness");
  // The message names file, pointer, expectation and finding.
  try {
    json d = base();
    d["masses"][0]["mass"] = -1;
    io::parse_mechanism(d, "x.json");
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()) ==
          "x.json: /masses/0/mass: expected a finite number in [1e-06, 1000000], found "
          "number -1");
  }
}
