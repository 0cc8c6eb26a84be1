// The mechanism's dissipation split (MechanismSystem::dissipate, conservative_rhs,
// correct_step) under method verlet, against exact references: an elastic ball bouncing
// on a one-sided plane keeps its energy to round-off (the contact kink corrected), a
// damped landing books exactly what it loses, a block pushed below the friction limit
// creeps at the regularised law's speed, a damped, frictional, draggy connection conserves
// momentum and closes its energy balance, and the quad hopper drop agrees with RODAS4.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/bench/suite.hpp"
#include "io/load/mechanism_loader.hpp"
#include "sim/ode/verlet.hpp"
#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"

using namespace pronk::pseudorigid;
using pronk::ode::Method;

namespace {

/// A 50 g ball dropped from 0.1 m onto the plane z = 0 (k = 1e5 N/m: omega h = 1.41 at
/// h = 1e-3 s), with the plane's damping b [N s/m].
Mechanism ball(double damping) {
  Mechanism m;
  add_mass(m, "ball", 0.05, Eigen::Vector3d(0, 0, 0.1));
  Surface s;
  s.nodes = {NodeRef{NodeRef::Kind::kMass, 0}};
  s.stiffness = 1e5;
  s.damping = damping;
  m.surfaces.push_back(s);
  m.simulation.t_end = 3.0;
  m.simulation.output_interval = 1e-3;
  m.simulation.solver.method = Method::kVerlet;
  m.simulation.solver.h_fixed = 1e-3;
  return m;
}

}  // namespace

TEST_CASE("verlet: an elastic ball keeps its energy exactly through contact", "[pseudorigid]") {
  // In flight Verlet's term T = h^2 (m g)^2 / 8m is constant, so E itself must return to
  // E0 after every bounce; the kink of the one-sided spring would cost up to
  // k v^2 h^2 / 8 = 0.05 J = 100 % of the energy per crossing without correct_step.
  const Mechanism m = ball(0.0);
  const RunSummary r = simulate(m);
  REQUIRE(r.status == RunStatus::kCompleted);
  const double e0 = r.energies.front().total();
  double worst = 0.0;
  int flights = 0;
  for (size_t i = 0; i < r.t.size(); ++i) {
    if (r.y[i][2] <= 0.0) continue;  // in contact: E differs from E - T by the contact force
    worst = std::max(worst, std::abs(r.energies[i].total() - e0));
    ++flights;
  }
  INFO("worst flight |E - E0| " << worst << " J of " << e0 << " J");
  CHECK(flights > 2000);
  CHECK(worst < 1e-11 * e0);        // round-off over 3000 steps
  CHECK(r.max_penetration > 1e-3);  // it did bounce (v = 1.4 m/s into 1e5 N/m: ~1 mm)
  // Inside the contact E departs from E - T by T = h^2 (k z)^2 / 8m, beyond 1e-2 of the
  // energy scale: the warning says so, and that the balance returned.
  INFO("worst balance " << r.energy_drift << " J, scale " << r.energy_scale << " J");
  REQUIRE(r.warnings.count("energy_balance_drift") == 1);
  const std::string& w = r.warnings.at("energy_balance_drift");
  CHECK(w.find("method verlet") != std::string::npos);
  CHECK(w.find("do not read this run as physics") == std::string::npos);
  // Apex heights: the ball returns to 0.1 m (the last apex before 3 s).
  double apex = 0.0;
  for (size_t i = r.t.size() / 2; i < r.t.size(); ++i) apex = std::max(apex, r.y[i][2]);
  CHECK(apex == Approx(0.1).epsilon(1e-4));
}

TEST_CASE("verlet: a damped landing books exactly the energy it loses", "[pseudorigid]") {
  // Critically damped plane (b h / 2m = 28: a damper far beyond explicit stability): the ball
  // lands plastically and the booked dissipation closes the balance to round-off in flight
  // and at rest.
  const Mechanism m = ball(2.0 * std::sqrt(1e5 * 0.05));
  const RunSummary r = simulate(m);
  REQUIRE(r.status == RunStatus::kCompleted);
  const double e0 = r.energies.front().total();
  double worst_flight = 0.0;
  for (size_t i = 0; i < r.t.size(); ++i) {
    if (r.y[i][2] > 0.0) {
      worst_flight = std::max(worst_flight, std::abs(r.energies[i].total() + r.dissipated[i] - e0));
    }
  }
  CHECK(worst_flight < 1e-12 * e0);
  // At rest on the plane (penetration m g / k) Verlet's term T = h^2 |F|^2 / 8m of the net
  // force is 0; in flight it was h^2 m g^2 / 8: E - T + D is the invariant.
  const double t_flight = 1e-6 * 0.05 * 9.81 * 9.81 / 8.0;
  CHECK(r.energies.back().total() + r.dissipated.back() == Approx(e0 - t_flight).epsilon(1e-9));
  CHECK(std::abs(r.y.back()[5]) < 1e-9);                                  // at rest
  CHECK(r.dissipated.back() == Approx(0.05 * 9.81 * 0.1).epsilon(1e-3));  // all of m g h
}

TEST_CASE("verlet: a block pushed below the friction limit creeps at the regularised speed",
          "[pseudorigid]") {
  // |F_t| = mu N v / sqrt(v^2 + vs^2) = F gives v = F vs / sqrt((mu N)^2 - F^2). The friction
  // is viscous with c = mu N / vs = 4.9e3 N s/m on 1 kg: h c / m = 4.9, far past explicit
  // stability; the split scheme's backward Euler reaches the exact creep speed.
  const double mass = 1.0, g = 9.81, k = 1e6, mu = 0.5, vs = 1e-3, f = 2.0;
  Mechanism m;
  m.gravity = Eigen::Vector3d(0, 0, -g);
  const NodeRef n = add_mass(m, "block", mass, Eigen::Vector3d(0, 0, -mass * g / k));
  Surface s;
  s.nodes = {n};
  s.stiffness = k;
  s.damping = 2.0 * std::sqrt(k * mass);
  s.friction = mu;
  s.slip_velocity = vs;
  m.surfaces.push_back(s);
  WorldForce push;
  push.node = n;
  push.force = Eigen::Vector3d(f, 0, 0);
  m.world_forces.push_back(push);
  m.simulation.t_end = 1.0;
  m.simulation.output_interval = 1e-2;
  m.simulation.solver.method = Method::kVerlet;
  m.simulation.solver.h_fixed = 1e-3;
  const RunSummary r = simulate(m);
  REQUIRE(r.status == RunStatus::kCompleted);
  const double n_force = mass * g;
  const double creep = f * vs / std::sqrt(mu * mu * n_force * n_force - f * f);
  CHECK(r.y.back()[3] / mass == Approx(creep).epsilon(1e-9));
  // The pushing force's work went into friction: E + D is constant (the world force's
  // potential -F x is part of E) once the block creeps, when the friction cancels the push and
  // the bounded term T_net is zero; before, T_net is below h^2 F^2 / 8m.
  const double first = r.energies[10].total() + r.dissipated[10];
  double worst = 0.0;
  for (size_t i = 10; i < r.t.size(); ++i) {
    worst = std::max(worst, std::abs(r.energies[i].total() + r.dissipated[i] - first));
  }
  CHECK(worst < 1e-12 * r.energy_scale);
  CHECK(r.energy_drift < 1e-3 * 1e-3 * f * f / (8.0 * mass));
}

TEST_CASE("verlet: a damped, frictional, draggy connection keeps momentum and its balance",
          "[pseudorigid]") {
  // Two free masses joined by a zero-rest-length spring (quadratic potential) with a damper
  // along it, linear friction and quadratic drag on the relative velocity. The pairwise
  // implicit updates conserve momentum exactly, and E - T + D is invariant
  // (T = h^2 |k d|^2 (1/m_a + 1/m_b) / 8).
  Mechanism m;
  m.gravity = Eigen::Vector3d::Zero();
  const double ma = 0.3, mb = 1.1, k = 2e3, h = 2e-3;
  const NodeRef a = add_mass(m, "a", ma, Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d(0, 2, 1));
  const NodeRef b = add_mass(m, "b", mb, Eigen::Vector3d(-0.1, 0.05, 0), Eigen::Vector3d(1, 0, 0));
  Connection c;
  c.a = a;
  c.b = b;
  c.stiffness = k;
  c.damping = 500.0;  // h b (1/ma + 1/mb) / 2 = 2.1
  c.friction = 3.0;
  c.drag = 40.0;
  m.connections.push_back(c);
  m.simulation.t_end = 1.0;
  m.simulation.output_interval = h;
  m.simulation.solver.method = Method::kVerlet;
  m.simulation.solver.h_fixed = h;
  const MechanismSystem sys(m);
  REQUIRE(sys.has_dissipation_split());
  auto momentum = [](const pronk::ode::Vec& y) {
    return Eigen::Vector3d(y.segment<3>(3) + y.segment<3>(9));
  };
  // The kicks' forces' term T = h^2 |k d|^2 (1/ma + 1/mb) / 8 (quadratic potential): the
  // split's booking D makes E - T + D exact; the stepper books with the held force instead,
  // moving T - T_net into its bounded term, so E - T_net + D_net is exact (T_net from the
  // stepper) and D_net - D = (T_net - T) - (T_net - T) at t = 0.
  auto kick_term = [&](const pronk::ode::Vec& y) {
    const Eigen::Vector3d d = y.segment<3>(0) - y.segment<3>(6);
    return h * h * k * k * d.squaredNorm() * (1.0 / ma + 1.0 / mb) / 8.0;
  };
  auto s = pronk::ode::make_stepper(m.simulation.solver, sys.dimension());
  pronk::ode::Vec y = m.initial_state();
  s->reset(sys, 0.0, y);
  const Eigen::Vector3d p0 = momentum(y);
  const double e0 = sys.energies(y).total();
  const double i0 = e0 - s->verlet_info()->verlet_term(), j0 = e0 - kick_term(y);
  const double gap0 = kick_term(y) - s->verlet_info()->verlet_term();
  double worst_p = 0.0, worst_e = 0.0, worst_kick = 0.0, worst_gap = 0.0;
  while (s->t() < m.simulation.t_end - 1e-12) {
    REQUIRE(s->step(sys, m.simulation.t_end) == pronk::ode::StepStatus::kOk);
    const pronk::ode::Vec& yi = s->y();
    const double e = sys.energies(yi).total(), d = s->verlet_info()->booked_dissipation();
    worst_p = std::max(worst_p, (momentum(yi) - p0).norm());
    worst_e = std::max(worst_e, std::abs(e - s->verlet_info()->verlet_term() + d - i0));
    const double gap = kick_term(yi) - s->verlet_info()->verlet_term();
    worst_kick = std::max(worst_kick, std::abs(e - kick_term(yi) + (d + gap - gap0) - j0));
    worst_gap = std::max(worst_gap, gap);
  }
  INFO("worst |E - T_net + D - I0| " << worst_e << ", T - T_net up to " << worst_gap << " J");
  CHECK(worst_p < 1e-13);
  CHECK(worst_e < 1e-12 * i0);
  CHECK(worst_kick < 1e-12 * i0);  // the same invariant through the kicks' term
  CHECK(worst_gap > 1e-3 * i0);    // the damper does cancel part of the force at times
  CHECK(s->verlet_info()->booked_dissipation() > 0.5 * i0);  // the relative motion is damped out
}

TEST_CASE("verlet: the dissipation split is not offered for a damped ghost under min_norm",
          "[pseudorigid]") {
  // Under the min_norm transfer an impulse on a ghost point moves the body masses by
  // matrices, not by the barycentric weights the implicit updates assume.
  Mechanism m;
  BodySpec spec;
  spec.inertia = Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal();
  std::string error;
  const int body = add_body(m, spec, &error);
  REQUIRE(body == 0);
  const NodeRef hip = add_ghost_point(m, body, "hip", Eigen::Vector3d(0.1, 0, -0.05));
  const NodeRef foot = add_mass(m, "foot", 0.01, Eigen::Vector3d(0.1, 0, -0.3));
  Connection leg;
  leg.a = foot;
  leg.b = hip;
  leg.stiffness = 100.0;
  leg.rest_length = 0.25;
  leg.damping = 1.0;
  m.connections.push_back(leg);
  CHECK(MechanismSystem(m).has_dissipation_split());
  m.simulation.ghost_transfer = GhostTransfer::kMinNorm;
  CHECK_FALSE(MechanismSystem(m).has_dissipation_split());
  m.connections.back().damping = 0.0;  // undamped: nothing to split off
  CHECK(MechanismSystem(m).has_dissipation_split());
}

TEST_CASE("verlet: the quad hopper drop against RODAS4", "[pseudorigid]") {
  // The benchmark scene (1e5 N/m critically damped ground with mu = 1 friction under 10 g
  // feet, 1e5 N/m internal springs), 2 s, three bounces. Measured at h = 2.5e-4 s: energy
  // balance at the flight apexes 3e-6 of the drop energy, apex heights within 0.3 mm of
  // RODAS4 at tol 1e-8 (0.2 % of the drop).
  const nlohmann::json doc = pronk::app::bench::quad_hopper_mechanism(2.0);
  const Mechanism base = pronk::io::parse_mechanism(doc, "<quad>").mechanism;
  auto apexes = [](const Mechanism& m, std::vector<double>* balance) {
    const RunSummary r = simulate(m);
    REQUIRE(r.status == RunStatus::kCompleted);
    const MechanismSystem sys(m);
    std::vector<double> z, out;
    for (const auto& y : r.y) z.push_back(sys.frames(y)[0].com.z());
    const double e0 = r.energies.front().total();
    for (size_t i = 1; i + 1 < z.size(); ++i) {
      if (z[i] > z[i - 1] && z[i] >= z[i + 1] && z[i] > z.front() - 0.075) {
        out.push_back(z[i]);
        if (balance != nullptr) {
          balance->push_back(std::abs(r.energies[i].total() + r.dissipated[i] - e0));
        }
      }
    }
    return out;
  };
  Mechanism ref = base;
  ref.simulation.solver.rtol = ref.simulation.solver.atol = 1e-8;
  const std::vector<double> z_ref = apexes(ref, nullptr);
  Mechanism v = base;
  v.simulation.solver.method = Method::kVerlet;
  v.simulation.solver.h_fixed = 2.5e-4;
  std::vector<double> balance;
  const std::vector<double> z = apexes(v, &balance);
  REQUIRE(z_ref.size() == 3);
  REQUIRE(z.size() == z_ref.size());
  const double drop = 0.15, drop_energy = v.total_mass() * 9.81 * drop;
  for (size_t i = 0; i < z.size(); ++i) {
    INFO("apex " << i << ": verlet " << z[i] << " m, rodas4 " << z_ref[i] << " m");
    CHECK(std::abs(z[i] - z_ref[i]) < 2e-3 * drop);
    CHECK(balance[i] < 2e-5 * drop_energy);
  }
}

TEST_CASE("verlet with an energy budget keeps every sample's balance near it", "[pseudorigid]") {
  // The elastic ball at h_fixed = 1e-3 s departs from its balance by h^2 (k z)^2 / 8m inside
  // each contact: up to the whole energy scale. With energy_tol = 1e-4 the 3 ms contacts are
  // sub-stepped (omega h = 1.41 at h_fixed: ~100 sub-steps) so that every sample stays within
  // the term (<= the budget) plus the offset of the step-size switches (measured 2.1e-4 of the
  // scale), and the flights are stepped at h_fixed.
  Mechanism m = ball(0.0);
  const RunSummary fixed = simulate(m);
  REQUIRE(fixed.status == RunStatus::kCompleted);
  const double tol = 1e-4;
  m.simulation.energy_tol = tol;
  const RunSummary r = simulate(m);
  REQUIRE(r.status == RunStatus::kCompleted);
  INFO("worst balance " << r.energy_drift / r.energy_scale << " of " << r.energy_scale
                        << " J (fixed step: " << fixed.energy_drift / fixed.energy_scale
                        << "), steps " << r.counters.steps_accepted << " vs "
                        << fixed.counters.steps_accepted);
  CHECK(fixed.energy_drift > 0.5 * fixed.energy_scale);
  CHECK(r.energy_drift < 3.0 * tol * r.energy_scale);
  CHECK(r.warnings.count("energy_balance_drift") == 0);
  CHECK(r.counters.steps_accepted < 2.5 * fixed.counters.steps_accepted);
  double apex = 0.0;
  for (size_t i = r.t.size() / 2; i < r.t.size(); ++i) apex = std::max(apex, r.y[i][2]);
  CHECK(apex == Approx(0.1).epsilon(5e-4));
}

TEST_CASE("verlet with an energy budget: the quad hopper's balance at every sample",
          "[pseudorigid]") {
  // The bench's drop (2 s, 4 landings): at h_fixed = 5e-4 s the impacts take the sampled
  // balance to 2.1e-3 of the energy scale; with energy_tol = 1e-4 it stays within that at
  // every 1 ms sample (4.4e-5 measured), for ~3 % more steps.
  pronk::pseudorigid::Mechanism m =
      pronk::io::parse_mechanism(pronk::app::bench::quad_hopper_mechanism(2.0), "<quad>").mechanism;
  m.simulation.solver.method = Method::kVerlet;
  m.simulation.solver.h_fixed = 5e-4;
  const RunSummary fixed = simulate(m);
  m.simulation.energy_tol = 1e-4;
  const RunSummary r = simulate(m);
  REQUIRE(fixed.status == RunStatus::kCompleted);
  REQUIRE(r.status == RunStatus::kCompleted);
  INFO("worst balance " << r.energy_drift / r.energy_scale << " (fixed "
                        << fixed.energy_drift / fixed.energy_scale << "), steps "
                        << r.counters.steps_accepted << ", rejected " << r.counters.steps_rejected);
  CHECK(fixed.energy_drift > 10.0 * 1e-4 * fixed.energy_scale);
  CHECK(r.energy_drift < 1e-4 * r.energy_scale);
  CHECK(r.counters.steps_accepted < 1.05 * fixed.counters.steps_accepted);
}
