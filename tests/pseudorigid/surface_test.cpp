// Surfaces (sim/pseudorigid/surface.hpp): a block sliding on a grounded plane with
// regularised Coulomb friction against the closed-form Coulomb solution, with the
// energy balance closing through the friction's dissipation.
#include <cmath>

#include <catch2/catch.hpp>

#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/simulator.hpp"

using namespace pronk::pseudorigid;

TEST_CASE("a block sliding on a frictional plane stops where Coulomb's law says",
          "[pseudorigid][surface]") {
  // 2 kg resting on a stiff plane (penetration m g / k = 2e-5 m), pushed along x at
  // 1.5 m/s: Coulomb deceleration mu g, stopping time v0 / (mu g), distance v0^2 / (2 mu g).
  const double mu = 0.6, g = 9.81, v0 = 1.5, mass = 2.0, k = 1e6;
  for (auto method : {pronk::ode::Method::kRodas4, pronk::ode::Method::kVerlet}) {
    Mechanism m;
    m.gravity = Eigen::Vector3d(0, 0, -g);
    const NodeRef n =
        add_mass(m, "block", mass, Eigen::Vector3d(0, 0, -mass * g / k), Eigen::Vector3d(v0, 0, 0));
    Surface s;
    s.nodes = {n};
    s.stiffness = k;
    s.damping = 2.0 * std::sqrt(k * mass);  // critically damped normal contact
    s.friction = mu;
    s.slip_velocity = 1e-4;
    m.surfaces.push_back(s);
    m.simulation.t_end = 0.5;
    m.simulation.output_interval = 1e-3;
    m.simulation.solver.method = method;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-9;
    m.simulation.solver.h_fixed = 2e-5;
    const RunSummary r = simulate(m);
    REQUIRE(r.status == RunStatus::kCompleted);
    const double t_stop = v0 / (mu * g), x_stop = v0 * v0 / (2 * mu * g);
    INFO("method " << static_cast<int>(method));
    // Mid-slide: x(t) = v0 t - mu g t^2 / 2.
    const size_t i = static_cast<size_t>(std::lround(0.1 / 1e-3));
    REQUIRE(r.t[i] == Approx(0.1));
    const double x_mid = v0 * 0.1 - 0.5 * mu * g * 0.01;
    CHECK(r.y[i][0] == Approx(x_mid).epsilon(1e-4));
    // After the stop, the block creeps no further than the regularisation allows.
    CHECK(r.y.back()[0] == Approx(x_stop).epsilon(1e-3));
    CHECK(std::abs(r.y.back()[3] / mass) < 1e-3);
    CHECK(t_stop < 0.5);
    // Energy balance: the kinetic energy went into friction (and the contact damper).
    const double e0 = 0.5 * mass * v0 * v0;
    CHECK(r.dissipated.back() == Approx(e0).epsilon(1e-3));
    CHECK(r.energy_drift < 1e-4 * e0);
  }
}
