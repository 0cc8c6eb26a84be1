// Validation cases (numbered as in docs/pseudorigid.md) on the pseudo-rigid model: free satellite
// (10), pendulum (11), energy exchange (9) and explicit instability (8), each against an
// independent reference (closed-form solutions, Euler's equations integrated separately, the
// elliptic-integral period).
#include <cmath>

#include <catch2/catch.hpp>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/math/rotation.hpp"
#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
#include "tests/pseudorigid/scenes.hpp"

using namespace pronk::pseudorigid;
namespace ts = pronk::pseudorigid::test_scenes;

namespace {

/// Euler's equations of a rigid body with a quaternion attitude (world omega out).
class EulerEquations final : public pronk::ode::OdeSystem {
 public:
  explicit EulerEquations(const Eigen::Vector3d& i) : i_(i) {}
  int dimension() const override { return 7; }
  void rhs(double, const pronk::ode::Vec& y, pronk::ode::Vec& f) const override {
    const Eigen::Quaterniond q(y[0], y[1], y[2], y[3]);
    const Eigen::Vector3d w = y.segment<3>(4);
    const Eigen::Quaterniond dq(0.0, w.x(), w.y(), w.z());
    const Eigen::Quaterniond qd = q * dq;
    f[0] = 0.5 * qd.w();
    f[1] = 0.5 * qd.x();
    f[2] = 0.5 * qd.y();
    f[3] = 0.5 * qd.z();
    f.segment<3>(4) = (-w.cross(i_.cwiseProduct(w))).cwiseQuotient(i_);
  }

 private:
  Eigen::Vector3d i_;
};

/// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean.
double elliptic_k(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return M_PI / (2.0 * a);
}

double omega_error(const Mechanism& m, const RunSummary& r) {
  MechanismSystem sys(m);
  const Eigen::Vector3d w = sys.body_omega(0, r.y.back());
  return (w - ts::satellite_omega(r.t.back())).norm() / ts::satellite_omega(0).norm();
}

}  // namespace

TEST_CASE("case 10: satellite precession, pseudo-rigid vs Euler's equations vs analytic",
          "[pseudorigid][validation]") {
  // Initial condition is the seed's.
  CHECK((ts::satellite_omega(0.0) - Eigen::Vector3d(0.0, 0.5, 1.251)).norm() < 1e-3);
  // Euler's equations (body frame) integrated numerically.
  EulerEquations euler(Eigen::Vector3d(1.0, 1.0, 0.25));
  const Eigen::Matrix3d r0 =
      pronk::math::euler_to_matrix(Eigen::Vector3d(M_PI, M_PI / 6, 0), pronk::math::EulerSet::k313);
  const Eigen::Quaterniond q0(r0);
  pronk::ode::Vec ye(7);
  ye << q0.w(), q0.x(), q0.y(), q0.z(), r0.transpose() * ts::satellite_omega(0.0);
  pronk::ode::SolverOptions eo;
  eo.rtol = eo.atol = 1e-13;
  auto es = pronk::ode::make_stepper(eo, 7);
  es->reset(euler, 0.0, ye);
  pronk::ode::integrate(euler, *es, 20.0, {}, eo);
  const Eigen::Quaterniond qe(es->y()[0], es->y()[1], es->y()[2], es->y()[3]);
  const Eigen::Vector3d we = qe.normalized() * Eigen::Vector3d(es->y().segment<3>(4));
  CHECK((we - ts::satellite_omega(20.0)).norm() < 1e-9);

  // Pseudo-rigid at a tight tolerance with stiff internal springs.
  Mechanism tight = ts::satellite(1e7, 20.0);
  tight.simulation.solver.rtol = 1e-8;
  tight.simulation.solver.atol = 1e-8;
  const RunSummary rt = simulate(tight);
  REQUIRE(rt.status == RunStatus::kCompleted);
  const double err_tight = omega_error(tight, rt);
  INFO("tight: omega error " << err_tight << ", steps " << rt.counters.steps_accepted);
  CHECK(err_tight <= 1e-6);
  // theta (angle between body z and the angular momentum, world z) stays constant.
  MechanismSystem sys(tight);
  double theta_dev = 0.0;
  for (const auto& y : rt.y) {
    const Eigen::Matrix3d r = sys.frames(y)[0].rotation;
    theta_dev = std::max(theta_dev, std::abs(std::acos(r(2, 2)) - M_PI / 6.0));
  }
  CHECK(theta_dev < 1e-6);

  // Loose tolerances drift visibly, and the drift shrinks as the tolerance tightens.
  double previous = 1e300;
  for (double tol : {1e-3, 1e-5}) {
    Mechanism m = ts::satellite(1e5, 20.0);
    m.simulation.solver.rtol = m.simulation.solver.atol = tol;
    const RunSummary r = simulate(m);
    REQUIRE(r.status == RunStatus::kCompleted);
    const double e = omega_error(m, r);
    INFO("tol " << tol << ": omega error " << e);
    if (tol == 1e-3) CHECK(e > 1e-3);
    CHECK(e < previous);
    previous = e;
  }
}

TEST_CASE("case 10 with velocity Verlet: the analytic precession at a fixed step, no drift",
          "[pseudorigid][validation]") {
  // k = 1e6 N/m: the fastest internal mode is ~2000 rad/s, so Verlet is stable below
  // h = 1e-3 s. Its error is O(h^2) in the rigid motion and bounded in the energy.
  double previous_energy = 1e300;
  for (double h : {5e-4, 2.5e-4}) {
    Mechanism m = ts::satellite(1e6, 20.0);
    m.simulation.solver.method = pronk::ode::Method::kVerlet;
    m.simulation.solver.h_fixed = h;
    const RunSummary r = simulate(m);
    REQUIRE(r.status == RunStatus::kCompleted);
    const double e = omega_error(m, r);
    const double drift = r.energy_drift / r.energy_scale;
    INFO("h " << h << ": omega error " << e << ", energy drift " << drift);
    // The model error of k = 1e6 (strain 1.8e-6) bounds the omega error from below.
    CHECK(e < 1e-5);
    CHECK(r.counters.rhs_evaluations == r.counters.steps_accepted + 1);
    CHECK(drift < 1e-6);
    CHECK(drift < 0.5 * previous_energy);  // O(h^2): halving h divides it by ~4
    previous_energy = drift;
  }
  // Beyond the stability limit (omega h > 2) the run ends as diverged, not as physics.
  Mechanism m = ts::satellite(1e6, 20.0);
  m.simulation.solver.method = pronk::ode::Method::kVerlet;
  m.simulation.solver.h_fixed = 1.5e-3;
  const RunSummary r = simulate(m);
  CHECK(r.status == RunStatus::kDiverged);
  CHECK(r.reason.find("stability limit") != std::string::npos);
}

TEST_CASE("case 11: large-amplitude pendulum period vs the elliptic-integral period",
          "[pseudorigid][validation]") {
  for (double amp_deg : {10.0, 150.0}) {
    const double amp = amp_deg * M_PI / 180.0;
    const double len = 1.0, g = 9.81;
    Mechanism m;
    m.gravity = Eigen::Vector3d(0, 0, -g);
    const NodeRef pivot = add_anchor(m, "pivot", Eigen::Vector3d::Zero());
    const NodeRef bob =
        add_mass(m, "bob", 1.0, Eigen::Vector3d(len * std::sin(amp), 0, -len * std::cos(amp)));
    Connection rod;
    rod.a = bob;
    rod.b = pivot;
    rod.stiffness = 1e9;  // stretch m g / k ~ 1e-8 m: model error ~1e-8
    rod.rest_length = len;
    // Start on the quasi-static stretched length so no rod vibration is excited.
    m.masses[0].position *= 1.0 + m.masses[0].mass * g * std::cos(amp) / (rod.stiffness * len);
    m.connections.push_back(rod);
    m.simulation.t_end = 4.0 * 4.0 * std::sqrt(len / g) * elliptic_k(std::sin(amp / 2)) + 0.1;
    // Crossings are interpolated linearly between samples; at the bottom x'' = 0, so
    // 1 ms samples locate them to ~1e-9 s.
    m.simulation.output_interval = 1e-3;
    m.simulation.solver.rtol = 1e-10;
    m.simulation.solver.atol = 1e-11;
    // RADAU5: the stiff rod swings (rotates), which RODAS4 resolves with ~50x more steps
    // (docs/pseudorigid.md); both solvers are validated, this case with the faster one.
    m.simulation.solver.method = pronk::ode::Method::kRadau5;
    const RunSummary r = simulate(m);
    INFO(r.reason);
    REQUIRE(r.status == RunStatus::kCompleted);
    // Downward crossings of x = 0 (bob passing the bottom moving in -x), interpolated.
    std::vector<double> crossings;
    for (size_t i = 1; i < r.t.size(); ++i) {
      const double x0 = r.y[i - 1][0], x1 = r.y[i][0];
      if (x0 > 0.0 && x1 <= 0.0)
        crossings.push_back(r.t[i - 1] + (r.t[i] - r.t[i - 1]) * x0 / (x0 - x1));
    }
    REQUIRE(crossings.size() >= 4);
    const double period = (crossings[3] - crossings[0]) / 3.0;
    const double exact = 4.0 * std::sqrt(len / g) * elliptic_k(std::sin(amp / 2));
    INFO("amplitude " << amp_deg << " deg: period " << period << " exact " << exact << ", "
                      << r.counters.steps_accepted << " steps");
    CHECK(std::abs(period - exact) / exact < 1e-6);
  }
}

namespace {

/// Case 9 (Ridgely 2001, fig. 3.5), reduced to one vertical leg: a 1.5 kg body mass on a
/// 500 N/m leg spring to a 0.05 kg foot, dropped on a conservative ground plane.
/// (The four-leg body version is the next test.)
Mechanism drop_test(double rtol) {
  Mechanism m;
  m.name = "drop_test";
  const NodeRef body = add_mass(m, "body", 1.5, Eigen::Vector3d(0, 0, 0.35));
  const NodeRef foot = add_mass(m, "foot", 0.05, Eigen::Vector3d(0, 0, 0.20));
  Connection leg;
  leg.name = "leg";
  leg.a = foot;
  leg.b = body;
  leg.kind = ConnectionClass::kLeg;
  leg.stiffness = 500.0;
  leg.rest_length = 0.15;
  m.connections.push_back(leg);
  Surface ground;
  ground.name = "ground";
  ground.type = SurfaceType::kPlane;
  ground.stiffness = 1e5;
  ground.nodes = {foot};
  m.surfaces.push_back(ground);
  m.simulation.t_end = 12.0;
  m.simulation.output_interval = 1e-3;
  m.simulation.solver.rtol = rtol;
  m.simulation.solver.atol = rtol;
  return m;
}

}  // namespace

TEST_CASE("case 9: spring-legged hopper on a conservative ground keeps its energy over 20 bounces",
          "[pseudorigid][validation]") {
  const Mechanism m = drop_test(1e-9);
  const RunSummary r = simulate(m);
  INFO(r.reason);
  REQUIRE(r.status == RunStatus::kCompleted);
  int apexes = 0;
  double min_apex = 1e9, max_apex = -1e9, max_leg = 0.0, max_kin = 0.0;
  for (size_t i = 1; i < r.t.size(); ++i) {
    if (r.y[i - 1][5] > 0.0 && r.y[i][5] <= 0.0) {  // body momentum z changes sign
      ++apexes;
      min_apex = std::min(min_apex, r.y[i][2]);
      max_apex = std::max(max_apex, r.y[i][2]);
    }
    max_leg = std::max(max_leg, r.energies[i].leg);
    max_kin = std::max(max_kin, r.energies[i].kinetic);
  }
  INFO("apexes " << apexes << ", apex range " << min_apex << " .. " << max_apex << ", drift "
                 << r.energy_drift << " J of " << r.energy_scale << " J, steps "
                 << r.counters.steps_accepted);
  CHECK(apexes >= 20);
  CHECK(max_leg > 0.1 * max_kin);  // energy is exchanged with the leg spring
  // Total energy (kinetic + gravitational + leg + contact) kept to solver tolerance.
  // (Body apexes vary: energy also moves into the foot's oscillation on the leg.)
  CHECK(r.energy_drift / r.energy_scale < 1e-6);
}

TEST_CASE(
    "case 9: four-leg body with ghost-point hips and body-attached prismatic legs keeps "
    "its energy; the minimum-norm ghost transfer does not",
    "[pseudorigid][validation]") {
  // studies/mechanisms/four_leg_drop.json: a tilted 1.5 kg body, four 0.05 kg feet on
  // 500 N/m leg springs to ghost-point hips, each foot held on a line through its hip
  // that turns with the body, all feet on a conservative ground plane.
  const std::string path = std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/four_leg_drop.json";
  nlohmann::json doc = pronk::io::read_json_file(path);
  doc["simulation"]["t_end"] = 1.5;  // before the rocking mode tips it over (no friction)
  doc["simulation"]["rtol"] = 1e-6;
  doc["simulation"]["atol"] = 1e-6;
  doc["bodies"][0]["internal_stiffness"] = 1e5;
  Mechanism m = pronk::io::parse_mechanism(doc, path).mechanism;
  REQUIRE(m.simulation.ghost_transfer == GhostTransfer::kBarycentric);
  REQUIRE(m.bodies.size() == 1);
  const RunSummary r = simulate(m);
  INFO(r.reason);
  REQUIRE(r.status == RunStatus::kCompleted);
  // Body CoM height minima = bounces (the body's masses are the last four).
  const int first = m.bodies[0].first_mass;
  auto com_z = [&](size_t i) {
    double z = 0.0;
    for (int k = 0; k < 4; ++k) z += 0.25 * r.y[i][6 * (first + k) + 2];
    return z;
  };
  int bounces = 0;
  double max_leg = 0.0, max_kin = 0.0, max_tilt = 0.0;
  MechanismSystem sys(m);
  for (size_t i = 1; i + 1 < r.t.size(); ++i) {
    if (com_z(i) < com_z(i - 1) && com_z(i) <= com_z(i + 1)) ++bounces;
    max_leg = std::max(max_leg, r.energies[i].leg);
    max_kin = std::max(max_kin, r.energies[i].kinetic);
    const Eigen::Matrix3d rot = sys.frames(r.y[i])[0].rotation;
    max_tilt = std::max(max_tilt, std::acos(std::min(1.0, rot(2, 2))));
  }
  INFO("bounces " << bounces << ", drift " << r.energy_drift << " J of " << r.energy_scale
                  << " J, steps " << r.counters.steps_accepted << ", max tilt " << max_tilt);
  CHECK(bounces >= 3);
  CHECK(max_leg > 0.1 * max_kin);  // energy goes through the leg springs
  CHECK(max_tilt > 0.05);          // the body rotates: the surfaces turn with it
  // Measured 2.9e-5 of the scale at rtol 1e-6 (5.5e-6 at 1e-7).
  CHECK(r.energy_drift / r.energy_scale < 1e-4);

  // The seed's minimum-norm ghost transfer is not the gradient of the spring energy
  // of the barycentric hip position: the same run drifts by orders of magnitude more.
  m.simulation.ghost_transfer = GhostTransfer::kMinNorm;
  const RunSummary rm = simulate(m);
  INFO("min-norm drift " << rm.energy_drift << " J");
  CHECK(rm.energy_drift > 30.0 * r.energy_drift);
}

TEST_CASE("case 8: RK4 beyond its stability limit is reported as diverged, RODAS4 completes",
          "[pseudorigid][validation]") {
  // Four 1 kg masses, six 1e6 N/m springs: internal frequency ~2e3 rad/s, RK4
  // stability needs h < ~1.4e-3 s.
  Mechanism m = ts::satellite(1e6, 2.0);
  m.simulation.solver.method = pronk::ode::Method::kRk4;
  m.simulation.solver.h_fixed = 5e-3;
  const RunSummary bad = simulate(m);
  CHECK(bad.status == RunStatus::kDiverged);
  INFO(bad.reason);
  CHECK(bad.reason.find("energy blow-up") != std::string::npos);
  for (const auto& y : bad.y) REQUIRE(y.allFinite());
  CHECK(std::isfinite(bad.energy_drift));

  m.simulation.solver.h_fixed = 2e-4;  // inside the stability limit: fine
  CHECK(simulate(m).status == RunStatus::kCompleted);

  m.simulation.solver.method = pronk::ode::Method::kRodas4;
  m.simulation.solver.rtol = m.simulation.solver.atol = 1e-6;
  const RunSummary good = simulate(m);
  CHECK(good.status == RunStatus::kCompleted);
  CHECK(good.energy_drift / good.energy_scale < 1e-3);
}
