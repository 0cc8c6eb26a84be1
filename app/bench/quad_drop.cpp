// `pronk bench`'s quad hopper drop: the spring hopper MuJoCo is compared with, dropped in the
// pseudo-rigid model (four-mass and rigid body) per solver setting: cost, energy-balance drift
// and apex heights against a tight reference.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/bench/suite.hpp"
#include "io/load/mechanism_loader.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"

namespace pronk::app::bench {

namespace pr = pronk::pseudorigid;
using ode::Method;

nlohmann::json quad_hopper_mechanism(double t_end) {
  // 1.5 kg body with the seed's inertia; four prismatic 100 N/m legs of rest
  // length 0.25 m at the hips (+-0.14, +-0.115, -0.04) m; 10 g feet 0.15 m above the
  // ground. The ground is MuJoCo's default contact made equivalent: Coulomb friction
  // mu = 1 (regularised below 1 mm/s) and a critically damped normal spring
  // (b = 2 sqrt(k m_foot)), so the feet land plastically, as in the MuJoCo peer.
  // Legs and slides are undamped. (With frictionless, elastic contact this hopper is
  // unstable: the feet bounce in every stance, the body rocks from round-off on and
  // tips over after about 2.5 s, so that scene measures a fall, not a drop test.)
  // The energy error is the energy-balance drift: |E + dissipated - E0|.
  using nlohmann::json;
  const double hips[4][2] = {{0.14, 0.115}, {0.14, -0.115}, {-0.14, 0.115}, {-0.14, -0.115}};
  const char* names[4] = {"fl", "fr", "rl", "rr"};
  const double leg = 0.25, drop = 0.15, hip_z = -0.04;
  json body = {{"name", "body"},
               {"mass", 1.5},
               {"inertia", {0.0074, 0.0106, 0.0164}},
               {"com", {0.0, 0.0, drop + leg - hip_z}},
               {"internal_stiffness", 1e5},
               {"ghost_points", json::array()}};
  json masses = json::array(), connections = json::array(), surfaces = json::array();
  json ground_nodes = json::array();
  for (int i = 0; i < 4; ++i) {
    const std::string n = names[i];
    const json hip = {hips[i][0], hips[i][1], hip_z};
    body["ghost_points"].push_back({{"name", "hip_" + n}, {"position", hip}});
    masses.push_back(
        {{"name", "foot_" + n}, {"mass", 0.01}, {"position", {hips[i][0], hips[i][1], drop}}});
    connections.push_back({{"name", "leg_" + n},
                           {"a", "foot_" + n},
                           {"b", "hip_" + n},
                           {"class", "leg"},
                           {"stiffness", 100.0},
                           {"rest_length", leg}});
    surfaces.push_back({{"name", "slide_" + n},
                        {"type", "line"},
                        {"body", "body"},
                        {"point", hip},
                        {"direction", {0, 0, 1}},
                        {"nodes", {"foot_" + n}},
                        {"stiffness", 1e5}});
    ground_nodes.push_back("foot_" + n);
  }
  const double ground_k = 1e5, foot_mass = 0.01;
  surfaces.push_back({{"name", "ground"},
                      {"type", "plane"},
                      {"point", {0, 0, 0}},
                      {"direction", {0, 0, 1}},
                      {"nodes", ground_nodes},
                      {"stiffness", ground_k},
                      {"damping", 2.0 * std::sqrt(ground_k * foot_mass)},
                      {"friction", 1.0}});
  return {{"kind", "mechanism"},
          {"name", "quad_hopper_drop"},
          {"gravity", {0, 0, -9.81}},
          {"bodies", {body}},
          {"masses", masses},
          {"connections", connections},
          {"surfaces", surfaces},
          {"simulation",
           {{"t_end", t_end},
            {"output_interval", 1e-3},
            {"method", "rodas4"},
            {"rtol", 1e-6},
            {"atol", 1e-6}}}};
}

namespace {

/// One timed run of the quad hopper drop.
struct QuadDropSetting {
  Method method;
  double tol;  ///< rtol = atol (RODAS4) or the fixed step h [s] (Verlet)
  pr::ErrorNorm norm;
  double energy_tol = 0.0;  ///< Verlet: simulation.energy_tol (0: every step at h)
  bool rigid = false;       ///< the body as one rigid body
};

std::vector<QuadDropSetting> quad_drop_settings(bool quick) {
  std::vector<QuadDropSetting> settings;
  for (double tol : quick ? std::vector<double>{1e-5} : std::vector<double>{1e-4, 1e-5, 1e-6}) {
    for (auto norm : {pr::ErrorNorm::kState, pr::ErrorNorm::kBody}) {
      settings.push_back({Method::kRodas4, tol, norm});
    }
  }
  // Verlet with the dissipation split: the regularised friction (mu N / v_s per unit foot
  // mass, ~1e6 1/s in stance) and the contact damper are implicit, so the step is limited by
  // the 1e5 N/m springs on the 10 g feet (omega ~ 3200 rad/s: h < 6e-4 s).
  for (double h : quick ? std::vector<double>{5e-4} : std::vector<double>{5e-4, 2.5e-4, 1e-4}) {
    settings.push_back({Method::kVerlet, h, pr::ErrorNorm::kState});
  }
  // Verlet with an energy budget: 5e-4 s steps, the impacts sub-stepped so that Verlet's
  // bounded term stays within 1e-4 of the energy scale (8.9 J; 1e-4 of it is 3.9e-4 of the
  // drop energy) at every step.
  settings.push_back({Method::kVerlet, 5e-4, pr::ErrorNorm::kState, 1e-4});
  // The rigid body: RODAS4 (its Jacobian by differences) and Verlet as above; the feet on
  // their 1e5 N/m slides still bound Verlet's step.
  settings.push_back({Method::kRodas4, 1e-5, pr::ErrorNorm::kState, 0.0, true});
  settings.push_back({Method::kVerlet, 5e-4, pr::ErrorNorm::kState, 0.0, true});
  settings.push_back({Method::kVerlet, 5e-4, pr::ErrorNorm::kState, 1e-4, true});
  return settings;
}

std::vector<double> quad_drop_apex_heights(const pr::Mechanism& m, const pr::RunSummary& r,
                                           std::vector<size_t>* index) {
  // Body CoM height on the output grid; apexes are local maxima of z while the body moves
  // up then down (refined by a parabola through three samples); only the body's flight
  // apexes count (foot vibration makes tiny wiggles).
  const pr::MechanismSystem sys(m);
  std::vector<double> z, out;
  for (const auto& y : r.y) z.push_back(sys.frames(y)[0].com.z());
  for (size_t i = 1; i + 1 < z.size(); ++i) {
    if (z[i] > z[i - 1] && z[i] >= z[i + 1] && z[i] > z.front() - 0.075) {
      const double den = z[i - 1] - 2 * z[i] + z[i + 1];
      const double off = den != 0 ? 0.5 * (z[i - 1] - z[i + 1]) / den : 0.0;
      out.push_back(z[i] - 0.25 * (z[i - 1] - z[i + 1]) * off);
      if (index != nullptr) index->push_back(i);
    }
  }
  return out;
}

/// One setting run and measured against the reference apex heights `ref`.
nlohmann::json quad_drop_run(const QuadDropSetting& setting, pr::Mechanism m, double t_end,
                             const std::vector<double>& ref, int repeat) {
  const double tol = setting.tol;
  const pr::ErrorNorm norm = setting.norm;
  m.simulation.solver.method = setting.method;
  m.simulation.solver.rtol = m.simulation.solver.atol = tol;
  if (setting.method == Method::kVerlet) m.simulation.solver.h_fixed = tol;
  m.simulation.energy_tol = setting.energy_tol;
  m.simulation.error_norm = norm;
  // Timed `repeat` times (median) while a run is cheap; a run over 0.5 s (the stiff methods
  // at tight tolerances) once, so the bench stays within its budget.
  const Timed<pr::RunSummary> run = timed(
      repeat, [&] { return pr::simulate(m); },
      [](const pr::RunSummary&, double cpu) { return cpu > 0.5; });
  const pr::RunSummary& r = run.result;
  std::vector<size_t> at_apex;
  const std::vector<double> a = quad_drop_apex_heights(m, r, &at_apex);
  const double z0 = pr::MechanismSystem(m).frames(r.y.front())[0].com.z(), drop = 0.15;
  // Energy balance at the flight apexes, where the forces on the feet are small: the
  // hop-to-hop drift (case 6's criterion), without the transient of a fixed-step method
  // inside an impact (Verlet: E - E_modified = h^2 |F|^2 / 8m, up to ~1e-1 J while a
  // foot is stopped at h = 5e-4 s).
  const double balance0 = r.energies.front().total();
  double apex_balance = 0, apex_vs_ref = 0;
  std::vector<double> ae;
  for (size_t i : at_apex) {
    ae.push_back(r.energies[i].total());
    apex_balance = std::max(apex_balance, std::abs(r.energies[i].total() + r.dissipated[i] -
                                                   r.actuator_work[i] - balance0));
  }
  for (size_t i = 0; i < a.size() && i < ref.size(); ++i) {
    apex_vs_ref = std::max(apex_vs_ref, std::abs(a[i] - ref[i]) / drop);
  }
  double apex_err = 0;
  for (double h : a) apex_err = std::max(apex_err, std::abs(h - z0) / drop);
  const double e0 = r.energies.front().total();
  // Energy reference: the drop energy m g h (mechanical energy above the state
  // standing on the ground is not well defined in both tools; this is).
  const double drop_energy = m.total_mass() * 9.81 * drop;
  nlohmann::json row = {
      {"method", std::string(ode::to_string(setting.method))},
      {"body", setting.rigid ? "rigid" : "four_masses"},
      {"tol", setting.method == Method::kVerlet ? 0.0 : tol},
      {"h", setting.method == Method::kVerlet ? tol : 0.0},
      {"energy_tol", setting.energy_tol},
      {"norm", norm == pr::ErrorNorm::kBody ? "body" : "state"},
      {"t_end", t_end},
      {"status", std::string(pr::to_string(r.status))},
      {"cost_per_sim_s", run.cpu_s / t_end},
      {"energy_drift_rel", r.energy_drift / r.energy_scale},
      {"energy_error_rel", r.energy_drift / drop_energy},
      {"energy_error_apex_rel", apex_balance / drop_energy},
      {"apex_height_vs_reference_rel", ref.empty() ? -1.0 : apex_vs_ref},
      {"bounces", a.size()},
      {"apex_heights_m", a},
      {"apex_height_error_rel", apex_err},
      {"first_bounce_energy_loss_rel", ae.empty() ? 0.0 : (e0 - ae.front()) / drop_energy},
      {"max_strain", r.max_strain},
      {"max_penetration_m", r.max_penetration}};
  add_cost(row, cost_of(run, r.counters));
  return row;
}

}  // namespace

nlohmann::json quad_hopper_drop(const BenchConfig& c) {
  const double t_end = c.quick ? 2.0 : 10.0;
  const nlohmann::json doc = quad_hopper_mechanism(t_end);
  const pr::Mechanism base = io::parse_mechanism(doc, "<quad_hopper_drop>").mechanism;
  // The same hopper with its body as one rigid body (the mechanism's "rigid": true).
  nlohmann::json doc_rigid = doc;
  doc_rigid["bodies"][0]["rigid"] = true;
  const pr::Mechanism base_rigid =
      io::parse_mechanism(doc_rigid, "<quad_hopper_drop_rigid>").mechanism;
  // 10 s of the drop costs seconds per run on the stiff methods: those run once, the cheap
  // ones c.repeat times (quad_drop_run), so the bench stays within its budget.
  const std::vector<QuadDropSetting> settings = quad_drop_settings(c.quick);
  // The reference for the apex heights: RODAS4 at tol 1e-8 (not timed).
  // (The rigid rows against the rigid body's own reference: at 1e5 N/m the four-mass body
  // flexes by ~0.3 %, and the two differ by ~9 % of the drop in apex height.)
  std::vector<double> z_ref, z_ref_rigid;
  for (const bool rigid : {false, true}) {
    pr::Mechanism m = rigid ? base_rigid : base;
    m.simulation.solver.rtol = m.simulation.solver.atol = 1e-8;
    if (!rigid) m.simulation.error_norm = pr::ErrorNorm::kBody;
    const pr::RunSummary r = pr::simulate(m);
    if (r.status == pr::RunStatus::kCompleted) {
      (rigid ? z_ref_rigid : z_ref) = quad_drop_apex_heights(m, r, nullptr);
    }
  }
  nlohmann::json out = nlohmann::json::array();
  for (const QuadDropSetting& setting : settings) {
    out.push_back(quad_drop_run(setting, setting.rigid ? base_rigid : base, t_end,
                                setting.rigid ? z_ref_rigid : z_ref, c.repeat));
  }
  return out;
}

}  // namespace pronk::app::bench
