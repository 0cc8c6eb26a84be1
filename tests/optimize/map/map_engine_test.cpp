// The map engine against independent references: a cell's numbers recomputed
// from direct reduced::simulate runs, the spectral radius from
// analyze_stability, the measured duty against the duty axis, the bisected
// boundary against a dense scan of the same row, and the full model's trials
// against the pulse model's verdicts.
#include "optimize/map/map_engine.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "optimize/scenario.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/reduced/simulator.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "tests/optimize/map/map_test_support.hpp"
#include "tests/support/scenes.hpp"

namespace m = pronk::optimize::map;
namespace o = pronk::optimize;
namespace reduced = pronk::reduced;
using pronk::scene::ModelKind;

TEST_CASE("a cell's numbers equal direct simulations of its trials", "[map]") {
  const m::MapStudy st = pronk::test::tiny_map(4, 3, 6.0);
  const long cell = 1 * st.columns() + 2;  // row 1 (8 deg tilt), duty 0.333
  const m::CellResult c = m::compute_cell(st, cell);
  // Independent reference: the shipped scene, the overrides, the duty law and
  // the tilt written out by hand, each trial simulated directly.
  pronk::scene::Scene base = pronk::test::load_shipped(
      "case3_legged_pulse", {"/initial/position=[0, 0, 0.45]", "/initial/attitude_deg=[0, 0, 0]"});
  const double duty = st.axes[0].values[2];
  const double flight = 2.0 * std::sqrt(2.0 * base.controller.hop_height / base.gravity);
  base.pulse.duration = duty * flight / (1.0 - duty);
  base.initial.attitude = (base.initial.attitude * pronk::math::Quat(Eigen::AngleAxisd(
                                                       8.0 * M_PI / 180, Eigen::Vector3d::UnitX())))
                              .normalized();
  o::RandomScenarios spec;
  spec.seed = o::mix_seed(7, 1);  // study seed, row 1
  spec.tilt_hi = 10.0 * M_PI / 180;
  spec.lateral_hi = 0.4;
  o::ScenarioSet set;
  set.duration = 6.0;
  int stabilized[2] = {0, 0};
  for (int model = 0; model < 2; ++model) {
    for (long t = 0; t < 3; ++t) {
      pronk::scene::Scene sc = o::apply_scenario(base, o::sample_scenario(spec, t), set);
      sc.model = model == 0 ? ModelKind::kImpulse : ModelKind::kPulse;
      reduced::RunOptions opt;
      opt.record_trajectory = false;
      const reduced::RunResult run = reduced::simulate(sc, opt);
      const reduced::RunMetrics mm = reduced::compute_metrics(sc, run);
      const long n = static_cast<long>(run.strides.size());
      const bool ok = run.status == reduced::RunStatus::kCompleted && mm.settle_strides >= 0 &&
                      mm.settle_strides <= 30 && n - mm.settle_strides >= 3;
      const m::TrialOutcome& got = c.trials[static_cast<size_t>(model)][static_cast<size_t>(t)];
      CHECK(got.stabilized == ok);
      CHECK(got.settle_strides == mm.settle_strides);
      CHECK(got.strides == n);
      // (The reference builds its scene by another route: equal to rounding.)
      CHECK(got.duty_mean == Approx(mm.mean_duty).epsilon(1e-12));
      CHECK(got.peak_force == Approx(mm.peak_leg_force).epsilon(1e-12));
      stabilized[model] += ok ? 1 : 0;
    }
  }
  // Fractions of the summary (summaries of a whole map are per index; here we
  // summarize a map whose every cell is this one).
  std::vector<m::CellResult> all(static_cast<size_t>(st.cells()), c);
  for (long i = 0; i < st.cells(); ++i) all[static_cast<size_t>(i)].index = i;
  const m::CellSummary cs = m::summarize(st, all)[static_cast<size_t>(cell)];
  CHECK(cs.fraction[0] == Approx(stabilized[0] / 3.0));
  CHECK(cs.fraction[1] == Approx(stabilized[1] / 3.0));
  CHECK(cs.disagreements == cs.a_only + cs.b_only);
  CHECK(cs.value0 == duty);
  CHECK(cs.value1 == 8.0);
}

TEST_CASE("spectral radius, duty and disagreement counts of a map's cells", "[map]") {
  const m::MapStudy st = pronk::test::tiny_map(3, 2, 6.0);
  std::vector<m::CellResult> cells;
  for (long i = 0; i < st.cells(); ++i) cells.push_back(m::compute_cell(st, i));
  const auto sums = m::summarize(st, cells);
  for (long col = 0; col < st.columns(); ++col) {
    // Cells of one duty share one stride map: computed by row 0 only.
    CHECK(m::stability_owner(st, st.columns() + col) == col);
    CHECK(cells[static_cast<size_t>(col)].has_stability);
    CHECK_FALSE(cells[static_cast<size_t>(st.columns() + col)].has_stability);
    const pronk::scene::Scene s =
        m::scene_at(st, st.axes[0].values[static_cast<size_t>(col)], 0.0, ModelKind::kPulse);
    const double rho = reduced::analyze_stability(s).spectral_radius;
    CHECK(sums[static_cast<size_t>(col)].spectral_radius == rho);
    CHECK(sums[static_cast<size_t>(st.columns() + col)].spectral_radius == rho);
  }
  for (const auto& s : sums) {
    // The measured duty of trials that keep running is the axis value.
    if (s.fell_fraction == 0.0) CHECK(s.mean_duty == Approx(s.value0).margin(0.01));
    long a_only = 0, b_only = 0;
    const auto& c = cells[static_cast<size_t>(s.index)];
    for (size_t t = 0; t < 2; ++t) {
      a_only += c.trials[0][t].stabilized && !c.trials[1][t].stabilized;
      b_only += !c.trials[0][t].stabilized && c.trials[1][t].stabilized;
    }
    CHECK(s.a_only == a_only);
    CHECK(s.b_only == b_only);
  }
}

TEST_CASE("the bisected boundary agrees with a dense scan of the row", "[map][boundary]") {
  nlohmann::json doc = pronk::test::tiny_map_document(3, 2, 8.0);
  doc["axes"] = {{{"kind", "duty_cycle"}, {"range", {0.2, 0.4}}, {"count", 3}}};
  doc["boundary"] = {{"resolution", 0.004}};
  const m::MapStudy st = m::parse_map_study(doc, "t.json", ".");
  std::vector<m::CellResult> cells;
  for (long i = 0; i < st.cells(); ++i) cells.push_back(m::compute_cell(st, i));
  const auto sums = m::summarize(st, cells);
  const m::BoundaryResult bracket = m::initial_bracket(st, sums, 0);
  REQUIRE(bracket.status == "bisected");  // the seed controller fails between 0.2 and 0.4
  const m::BoundaryResult b = m::bisect_row(st, bracket);
  CHECK(b.bad - b.good <= st.resolution);
  CHECK(b.good >= bracket.good);
  CHECK(b.bad <= bracket.bad);
  CHECK(m::all_stabilized_at(st, 0, b.good, 0));
  CHECK_FALSE(m::all_stabilized_at(st, 0, b.bad, 0));
  // Dense scan of the bracket in steps of resolution / 2: the first failing
  // value is within one resolution of the bisected boundary.
  const double step = st.resolution / 2;
  double dense = bracket.bad;
  for (double v = bracket.good; v < bracket.bad; v += step) {
    if (!m::all_stabilized_at(st, 0, v, 0)) {
      dense = v;
      break;
    }
  }
  CHECK(std::abs(dense - b.bad) <= st.resolution + 1e-12);
  // Round trip of the journal records.
  const m::BoundaryResult back = m::boundary_from_json(m::to_json(b));
  CHECK(back.boundary == b.boundary);
  CHECK(back.probes == b.probes);
  const m::CellResult cb = m::cell_from_json(m::to_json(cells[1]));
  CHECK(cb.trials[1][0].duty_mean == cells[1].trials[1][0].duty_mean);
  CHECK(cb.spectral_radius == cells[1].spectral_radius);
}

TEST_CASE("derived and pointer axes change the cell scene as documented", "[map]") {
  nlohmann::json doc = pronk::test::tiny_map_document();
  doc["axes"] = {{{"kind", "velocity_kick"}, {"values", {0.1, 0.3}}},
                 {{"kind", "disturbance_direction_deg"}, {"values", {0, 90}}}};
  m::MapStudy st = m::parse_map_study(doc, "t.json", ".");
  pronk::scene::Scene s = m::scene_at(st, 0.3, 90, ModelKind::kPulse);
  CHECK(s.initial.velocity.x() == Approx(0.0).margin(1e-15));
  CHECK(s.initial.velocity.y() == Approx(0.3));
  CHECK(s.model == ModelKind::kPulse);
  doc["axes"] = {{{"kind", "disturbance_direction_deg"}, {"values", {0, 180}}, {"magnitude", 0.2}},
                 {{"kind", "lateral_offset"}, {"values", {-0.1, 0.2}}}};
  st = m::parse_map_study(doc, "t.json", ".");
  s = m::scene_at(st, 180, 0.2, ModelKind::kImpulse);
  CHECK(s.initial.velocity.x() == Approx(-0.2));
  CHECK(s.initial.position.y() == Approx(0.2));
  CHECK(s.model == ModelKind::kImpulse);
  doc["axes"] = {
      {{"kind", "tilt_deg"}, {"axis", {0, 2, 0}}, {"values", {0, 30}}},
      {{"kind", "pointer"}, {"pointer", "/controller/bank/kp"}, {"values", {0.01, 0.2}}}};
  st = m::parse_map_study(doc, "t.json", ".");
  s = m::scene_at(st, 30, 0.2, ModelKind::kPulse);
  CHECK(s.controller.bank_kp == 0.2);
  const Eigen::Vector3d z = s.initial.attitude * Eigen::Vector3d::UnitZ();
  CHECK(std::acos(z.z()) == Approx(30.0 * M_PI / 180));  // tilted 30 deg about body y
  CHECK(z.x() == Approx(0.5));
  // Cells differing only in a pointer axis have their own stride map.
  CHECK(m::stability_owner(st, 3) == 2);  // row 1, column 1 -> row 1, column 0
}

TEST_CASE("row seeding shares a row's disturbances, cell seeding draws per cell", "[map]") {
  nlohmann::json doc = pronk::test::tiny_map_document(3, 2, 5.0);
  m::MapStudy st = m::parse_map_study(doc, "t.json", ".");
  auto kick = [&](long cell, long t) {
    const o::Scenario s = m::trial_scenario(st, m::cell_seed_key(st, cell), t);
    return Eigen::Vector2d(s.position_offset.y(), s.tilt.x());
  };
  CHECK(kick(0, 0) == kick(2, 0));  // same row
  CHECK(kick(0, 0) != kick(3, 0));  // next row
  CHECK(kick(0, 0) != kick(0, 1));  // next trial
  doc["trials"]["seeding"] = "cell";
  st = m::parse_map_study(doc, "t.json", ".");
  CHECK(kick(0, 0) != kick(2, 0));
  CHECK(m::cell_seed_key(st, 4) == 4);
  // Every draw depends on (seed, key, trial) only.
  CHECK(kick(4, 1) == kick(4, 1));
  const m::CellResult a = m::compute_cell(st, 4), b = m::compute_cell(st, 4);
  CHECK(m::to_json(a).dump() == m::to_json(b).dump());
}

TEST_CASE("a pseudo-rigid map trial agrees with the pulse model's verdict at low duty",
          "[map][pseudo_rigid][heavy]") {
  // The robot in the full model with force legs and stiff (1e6 N/m) body springs is the
  // pulse model's rigid body on massless legs up to the body's elasticity: at 12 % duty
  // (far below the seed's ~29 % limit) both models must judge every trial alike. Trials of
  // the map's default 12 s: settling (within one stride of the pulse model's) is then far
  // from the end of the run (in 8 s one trial settles at stride 14 of 17 in the pulse
  // model and at 15 in the full model: too late to hold 3 strides; a borderline verdict).
  nlohmann::json doc = pronk::test::tiny_map_document(1, 2, 12.0);
  doc["models"] = {"pulse", "pseudo_rigid"};
  doc["scene_overrides"].push_back(R"(/pseudo_rigid={"legs": "force", "internal_stiffness": 1e6, )"
                                   R"("position_trim_gain": 0, "attitude_trim_gain": 0})");
  doc["axes"] = {{{"kind", "duty_cycle"}, {"values", {0.12}}}};
  const m::MapStudy st = m::parse_map_study(doc, "t.json", ".");
  const m::CellResult c = m::compute_cell(st, 0);
  REQUIRE(c.trials.size() == 2);
  long stabilized = 0;
  for (size_t t = 0; t < 2; ++t) {
    const m::TrialOutcome& pulse = c.trials[0][t];
    const m::TrialOutcome& full = c.trials[1][t];
    INFO("trial " << t << ": pulse " << pulse.status << " settle " << pulse.settle_strides
                  << ", pseudo_rigid " << full.status << " settle " << full.settle_strides);
    CHECK(full.stabilized == pulse.stabilized);
    CHECK(full.status == pulse.status);
    CHECK(full.strides == pulse.strides);
    CHECK(full.duty_mean == Approx(pulse.duty_mean).epsilon(0.01));
    if (pulse.stabilized) CHECK(std::abs(full.settle_strides - pulse.settle_strides) <= 1);
    stabilized += pulse.stabilized ? 1 : 0;
  }
  CHECK(stabilized >= 1);  // the comparison covers stabilized trials
  // The cell's spectral radius is the full model's estimate; the pulse model's stride map
  // at the same duty is the reference (the rigid limit of the same robot).
  REQUIRE(c.has_stability);
  const double rho_pulse =
      reduced::analyze_stability(m::scene_at(st, 0.12, 0, ModelKind::kPulse)).spectral_radius;
  CHECK(c.spectral_radius == Approx(rho_pulse).margin(0.01));
  // Trial 0 by hand: the cell scene, the drawn disturbance, robot::simulate, the metrics.
  pronk::scene::Scene sc = o::apply_scenario(m::scene_at(st, 0.12, 0, ModelKind::kPseudoRigid),
                                             m::trial_scenario(st, 0, 0), st.trial_set);
  pronk::robot::RobotRunOptions ro;
  ro.record_trajectory = false;
  const pronk::robot::RobotRunResult r = pronk::robot::simulate(sc, ro);
  const reduced::RunMetrics mm = reduced::compute_metrics(sc, r.run);
  CHECK(c.trials[1][0].settle_strides == mm.settle_strides);
  CHECK(c.trials[1][0].strides == static_cast<long>(r.run.strides.size()));
  CHECK(c.trials[1][0].peak_force == mm.peak_leg_force);
}
