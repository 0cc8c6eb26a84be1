// The probe of "method": "auto" (sim/pseudorigid/scene_probe.hpp): its highest natural
// frequency against closed forms, and against velocity Verlet's real stability limit on the
// shipped satellite and pendulum (stable just below 2 / omega_max, diverging just above).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/scene_probe.hpp"
#include "sim/pseudorigid/simulator.hpp"

namespace pr = pronk::pseudorigid;
namespace io = pronk::io;
using Catch::Matchers::WithinRel;

namespace {

const std::string kDir = std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/";

pr::Connection spring(const pr::NodeRef& a, const pr::NodeRef& b, double k, double rest) {
  pr::Connection c;
  c.name = "s";
  c.a = a;
  c.b = b;
  c.stiffness = k;
  c.rest_length = rest;
  return c;
}

pr::Surface surface(pr::SurfaceType type, const pr::NodeRef& n, double k) {
  pr::Surface s;
  s.name = "s";
  s.type = type;
  s.direction = Eigen::Vector3d::UnitZ();
  s.nodes = {n};
  s.stiffness = k;
  return s;
}

/// The shipped scene with verlet at h_fixed = h, run for t_end.
pr::RunStatus verlet_status(const std::string& scene, double h, double t_end) {
  nlohmann::json doc = io::read_json_file(kDir + scene);
  doc["simulation"]["method"] = "verlet";
  doc["simulation"]["h_fixed"] = h;
  doc["simulation"]["t_end"] = t_end;
  return pr::simulate(io::parse_mechanism(doc, scene).mechanism).status;
}

}  // namespace

TEST_CASE("probe: a spring between two free masses rings at sqrt(k (1/m1 + 1/m2))",
          "[pseudorigid][auto]") {
  pr::Mechanism m;
  const pr::NodeRef a = pr::add_mass(m, "a", 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const pr::NodeRef b =
      pr::add_mass(m, "b", 3.0, Eigen::Vector3d(0.3, 0.1, 0.0), Eigen::Vector3d::Zero());
  m.connections.push_back(spring(a, b, 1e4, std::hypot(0.3, 0.1)));  // at rest: no tension
  const pr::SceneProbe p = pr::probe_scene(m);
  CHECK_THAT(p.omega_max, WithinRel(std::sqrt(1e4 * (1.0 + 1.0 / 3.0)), 1e-6));
  CHECK(p.omega_bound >= p.omega_max);
  CHECK(p.min_mass == 1.0);
  CHECK_FALSE(p.contact);
  CHECK_FALSE(p.dissipation);
  CHECK(p.springs == 1);
}

TEST_CASE("probe: directions count (a foot on a slide and the ground), Gershgorin does not",
          "[pseudorigid][auto]") {
  // A 1 g foot on a vertical grounded line (1e5 N/m across) pressed on the ground
  // (4e4 N/m along z): the largest mode is the slide's, sqrt(1e5 / 1e-3); summing the two
  // stiffnesses on the foot, as Gershgorin's bound does, overestimates it.
  pr::Mechanism m;
  const pr::NodeRef foot =
      pr::add_mass(m, "foot", 1e-3, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  m.surfaces.push_back(surface(pr::SurfaceType::kLine, foot, 1e5));
  m.surfaces.push_back(surface(pr::SurfaceType::kPlane, foot, 4e4));
  m.surfaces.back().damping = 1.0;
  const pr::SceneProbe p = pr::probe_scene(m);
  CHECK_THAT(p.omega_max, WithinRel(std::sqrt(1e5 / 1e-3), 1e-6));
  CHECK_THAT(p.omega_bound, WithinRel(std::sqrt(1.4e5 / 1e-3), 1e-6));
  CHECK(p.contact);
  CHECK(p.dissipation);
  CHECK(p.dissipation_split);
}

TEST_CASE("probe: a zero-rest-length spring is isotropic", "[pseudorigid][auto]") {
  pr::Mechanism m;
  const pr::NodeRef a =
      pr::add_mass(m, "a", 2.0, Eigen::Vector3d(0.0, 0.0, -1.0), Eigen::Vector3d::Zero());
  const pr::NodeRef p0 = pr::add_anchor(m, "p", Eigen::Vector3d::Zero());
  m.connections.push_back(spring(a, p0, 800.0, 0.0));
  // Along and across: k / m in all three directions.
  CHECK_THAT(pr::probe_scene(m).omega_max, WithinRel(std::sqrt(800.0 / 2.0), 1e-6));
  // With its rest length the across directions only carry the (zero) tension.
  m.connections.back().rest_length = 1.0;
  CHECK_THAT(pr::probe_scene(m).omega_max, WithinRel(std::sqrt(800.0 / 2.0), 1e-6));
  m.connections.clear();
  CHECK(pr::probe_scene(m).omega_max == 0.0);
}

TEST_CASE("probe: 2 / omega_max is verlet's real stability limit on the shipped scenes",
          "[pseudorigid][auto]") {
  for (const std::string scene : {"satellite.json", "pendulum.json"}) {
    INFO(scene);
    nlohmann::json doc = io::read_json_file(kDir + scene);
    const pr::SceneProbe p = pr::probe_scene(io::parse_mechanism(doc, scene).mechanism);
    const double limit = 2.0 / p.omega_max;
    CHECK(verlet_status(scene, 0.97 * limit, 3.0) == pr::RunStatus::kCompleted);
    CHECK(verlet_status(scene, 1.05 * limit, 3.0) == pr::RunStatus::kDiverged);
    // Gershgorin's bound is safe but loose here.
    CHECK(p.omega_bound >= p.omega_max);
  }
}
