// End-to-end test of `pronk bench --quick` (docs/performance.md): the JSON it writes is
// complete and finite, and its numbers agree with independent references —
// the satellite's analytic precession, the known orders of the fixed-step
// methods, the energy balance of the quad hopper drop, and, when the
// CVODE peer is built, an independent integrator of the same right-hand side.
// No timing assertions: timing claims are benchmarks, not tests.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

/// Every number finite, no null anywhere (nlohmann writes NaN as null).
void check_finite_json(const json& j, const std::string& where = "") {
  INFO("at " << (where.empty() ? "/" : where));
  REQUIRE_FALSE(j.is_null());
  if (j.is_number_float()) CHECK(std::isfinite(j.get<double>()));
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) check_finite_json(*it, where + "/" + it.key());
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) check_finite_json(j[i], where + "/" + std::to_string(i));
  }
}

/// The work-precision points of one problem and solver (and variant, if given).
std::vector<json> points(const json& doc, const std::string& problem, const std::string& solver,
                         const std::string& variant = "*") {
  std::vector<json> out;
  for (const auto& p : doc["work_precision"]) {
    if (p["problem"] == problem && p["solver"] == solver &&
        (variant == "*" || p["variant"] == variant)) {
      out.push_back(p);
    }
  }
  return out;
}

const json* at_tol(const std::vector<json>& pts, double tol) {
  for (const auto& p : pts) {
    if (p["tol"].get<double>() == tol) return &p;
  }
  return nullptr;
}

/// Runs `pronk bench --quick` once per process (Catch2 re-enters the test case
/// for every section) and returns its output directory.
const TempDir& quick_bench(int* code, std::string* err) {
  static TempDir dir("bench");
  static Run r = pronk(dir, {"bench", "--quick", "--out", "out", "-q"});
  *code = r.code;
  *err = r.err;
  return dir;
}

}  // namespace

TEST_CASE("pronk bench --quick writes complete, finite results that match the references",
          "[cli][bench][heavy]") {
  int code = -1;
  std::string err;
  const TempDir& dir = quick_bench(&code, &err);
  INFO("stderr: " << err);
  REQUIRE(code == 0);
  const json doc = json::parse(slurp(dir / "out/bench.json"));
  check_finite_json(doc);
  CHECK(doc["quick"] == true);
  CHECK_FALSE(doc["machine"].get<std::string>().empty());
  CHECK(fs::file_size(dir / "out/work_precision.csv") > 100);
  CHECK(fs::file_size(dir / "out/fidelity_ladder.csv") > 100);
  CHECK(fs::exists(dir / "out/satellite_work_precision.gp"));
  CHECK(fs::exists(dir / "out/hopper_work_precision.gp"));
  // method auto against the grid: every shipped mechanism scene, the quad hopper and
  // pr_running, auto's run meets its accuracy (timings are not checked).
  const json& autos = doc["auto_check"]["scenes"];
  CHECK(autos.size() == 7);
  for (const json& a : autos) {
    INFO(a["scene"]);
    CHECK(a["auto"]["meets"] == true);
    CHECK_THAT(a["choice"].get<std::string>(), Catch::Matchers::StartsWith("auto: "));
    CHECK(a["best"].is_object());
    CHECK(a["ratio"].get<double>() > 0.0);
  }

  // CSV: one row per work-precision point, same column count everywhere.
  {
    std::istringstream in(slurp(dir / "out/work_precision.csv"));
    std::string line;
    std::getline(in, line);
    const auto columns = std::count(line.begin(), line.end(), ',');
    size_t rows = 0;
    while (std::getline(in, line)) {
      CHECK(std::count(line.begin(), line.end(), ',') == columns);
      ++rows;
    }
    CHECK(rows == doc["work_precision"].size());
  }

  SECTION("satellite: RODAS4 converges to the analytic precession as the tolerance tightens") {
    for (const std::string norm : {"state", "body"}) {
      const auto pts = points(doc, "satellite", "rodas4", norm);
      const json* loose = at_tol(pts, 1e-3);
      const json* tight = at_tol(pts, 1e-7);
      REQUIRE(loose != nullptr);
      REQUIRE(tight != nullptr);
      INFO(norm << " norm: " << loose->dump() << "\n" << tight->dump());
      CHECK((*tight)["errors"]["omega_final"].get<double>() <
            1e-2 * (*loose)["errors"]["omega_final"].get<double>());
      CHECK((*tight)["steps"].get<long>() > (*loose)["steps"].get<long>());
    }
    // Against the analytic solution (issue 3: 1e-5 is the accuracy the ratios are taken at).
    const auto state_pts = points(doc, "satellite", "rodas4", "state");
    const json* tight = at_tol(state_pts, 1e-7);
    REQUIRE(tight != nullptr);
    CHECK((*tight)["errors"]["omega_final"].get<double>() < 1e-5);
    // Independent explicit integrator on the same scene agrees as well.
    const auto dopri_pts = points(doc, "satellite", "dopri5");
    const json* dopri = at_tol(dopri_pts, 1e-7);
    REQUIRE(dopri != nullptr);
    CHECK((*dopri)["errors"]["omega_final"].get<double>() < 1e-5);
    // Velocity Verlet below its stability limit: the same answer, one RHS per step.
    const auto verlet = points(doc, "satellite", "verlet");
    REQUIRE(verlet.size() >= 2);
    for (const auto& p : verlet) {
      CHECK(p["status"] == "completed");
      CHECK(p["errors"]["omega_final"].get<double>() < 1e-5);
      CHECK(p["rhs"].get<long>() == p["steps"].get<long>() + 1);
    }
    const json& fastest = doc["headline"]["satellite"]["fastest"];
    CHECK(fastest["omega_final"].get<double>() <= 1e-5);
  }

  SECTION(
      "satellite: Euler and RK2 beyond their stability limit end diverged (Ridgely 2001, fig. "
      "3.4)") {
    for (const std::string s : {"euler", "rk2"}) {
      const auto pts = points(doc, "satellite", s);
      REQUIRE_FALSE(pts.empty());
      for (const auto& p : pts) {
        CHECK(p["status"] == "diverged");
        CHECK(p["errors"].empty());
      }
    }
    for (const auto& p : points(doc, "satellite", "rk4")) CHECK(p["status"] == "completed");
  }

  SECTION("stiffness sweep covers 1e4 and 1e8 N/m and every run completes") {
    std::map<double, int> seen;
    for (const auto& p : points(doc, "satellite_stiffness", "rodas4")) {
      CHECK(p["status"] == "completed");
      seen[p["stiffness"].get<double>()]++;
    }
    CHECK(seen[1e4] == 2);
    CHECK(seen[1e8] == 2);
    const json& g = doc["headline"]["stiffness_growth"];
    CHECK(g["rodas4_state_norm"]["ratio"].get<double>() > 0);
    for (const std::string solver : {"radau5", "verlet"}) {
      const auto pts = points(doc, "satellite_stiffness", solver);
      // --quick: RADAU5 at tol 1e-6 and 1e-8 per stiffness, Verlet at one step.
      REQUIRE(pts.size() == (solver == "radau5" ? 4u : 2u));
      for (const auto& p : pts) {
        CHECK(p["status"] == "completed");
        CHECK(p["errors"].contains("omega_final_ref"));
        CHECK(p["errors"].contains("model_omega_error"));
      }
      CHECK(g[solver]["ratio"].get<double>() > 0);
    }
    // Issue 23: at omega error <= 1e-5 against each stiffness's reference the fastest stiff
    // method is found at both ends; RADAU5 (stage Jacobians at 1e8 N/m) takes fewer steps at
    // 1e8 than at 1e4 (measured 807 vs 6667; the timings themselves are not checked).
    const json& best = g["matched"]["best_stiff"];
    REQUIRE(best["points"].size() == 2);
    for (const auto& p : best["points"]) REQUIRE(p.value("found", true));
    CHECK(best["points"][1]["steps"].get<long>() < best["points"][0]["steps"].get<long>());
    // The target: 1e-5, or the model's own error where that is larger; each chosen
    // point is within it, and the strict variant (1e-5 everywhere) is reported beside it.
    CHECK(g["matched"]["limit_includes_model_error"] == true);
    for (const auto& p : best["points"]) {
      const double limit = std::max(1e-5, p["model_omega_error"].get<double>());
      CHECK(p["omega_final_ref"].get<double>() <= limit);
    }
    REQUIRE(g.contains("matched_strict"));
    CHECK(g["matched_strict"]["limit_includes_model_error"] == false);
    for (const auto& p : g["matched_strict"]["best_stiff"]["points"]) {
      if (p.value("found", true)) CHECK(p["omega_final_ref"].get<double>() <= 1e-5);
    }
    // Verlet at half its stability limit: steps grow like sqrt(k), 100x over the sweep.
    CHECK(g["verlet"]["steps_ratio"].get<double>() == Approx(100.0).epsilon(0.01));
  }

  SECTION("hopper: fitted orders of the fixed-step methods are 1, 2 and 4") {
    std::map<std::string, double> order;
    for (const auto& o : doc["orders"]) {
      CHECK(o["points"].get<int>() >= 3);
      order[o["solver"].get<std::string>()] = o["order"].get<double>();
    }
    REQUIRE(order.size() == 3);
    CHECK(order["euler"] == Approx(1.0).margin(0.15));
    CHECK(order["rk2"] == Approx(2.0).margin(0.2));
    CHECK(order["rk4"] == Approx(4.0).margin(0.4));
    // DOPRI5: the tightest tolerance is at least as accurate as the loosest.
    const auto d = points(doc, "hopper", "dopri5");
    REQUIRE(d.size() >= 2);
    CHECK(at_tol(d, 1e-9)->at("errors")["final_state"].get<double>() <=
          at_tol(d, 1e-3)->at("errors")["final_state"].get<double>());
    CHECK(at_tol(d, 1e-9)->at("errors")["touchdown_time"].get<double>() < 1e-6);
    for (const auto& p : points(doc, "hopper_stride_map", "dopri5")) {
      CHECK(p["errors"]["fixed_point"].get<double>() < 1e-6);
    }
  }

  SECTION("fidelity ladder: impulse and pulse run and are stable; pseudo-rigid skipped in quick") {
    std::map<std::string, json> by;
    for (const auto& p : doc["fidelity_ladder"]) by[p["model"].get<std::string>()] = p;
    REQUIRE(by.count("impulse"));
    REQUIRE(by.count("pulse"));
    REQUIRE(by.count("pseudo_rigid"));
    CHECK(by["impulse"]["stable"] == true);
    CHECK(by["pulse"]["stable"] == true);
    CHECK(by["pulse"]["mean_duty"].get<double>() > 0.1);
    CHECK(by["pulse"]["mean_duty"].get<double>() < 0.3);
    // Both models hop to about leg length + hop height (0.25 + 0.2 m).
    CHECK(by["impulse"]["mean_apex_m"].get<double>() == Approx(0.45).margin(0.01));
    CHECK(by["pulse"]["apex_rms_vs_impulse_m"].get<double>() < 0.02);
    CHECK(by["pseudo_rigid"]["available"] == false);
    CHECK(by["pseudo_rigid"]["status"] == "skipped");
    // The stride-map fit (the pseudo-rigid rung's estimator) against the stride map of the
    // reduced rungs (finite differences of the map): the tolerance of the estimator's own test.
    for (const std::string m : {"impulse", "pulse"}) {
      INFO(by[m].dump());
      CHECK(by[m]["spectral_radius_method"] == "stride_map");
      CHECK(by[m]["fit_ok"] == true);
      CHECK(by[m]["fit_residual_rel"].get<double>() < 0.01);
      CHECK(std::abs(by[m]["spectral_radius_fit"].get<double>() -
                     by[m]["spectral_radius"].get<double>()) < 2e-3);
    }
    CHECK(fs::file_size(dir / "out/fidelity_robustness.csv") > 100);
  }

  SECTION("ladder robustness: the reduced rungs reproduce the shipped map's trials") {
    const json& rb = doc["fidelity_robustness"];
    CHECK(rb["duties"] == json({0.1, 0.2, 0.3, 0.4}));
    CHECK(rb["trials_per_cell"] == 8);
    CHECK(rb["seed"] == 261);
    CHECK(rb["trial_duration_s"] == 12.0);
    // Independent reference: the committed `pronk map studies/map_seed_duty.json` run, row 0
    // (no extra roll), its first 8 trials at these duties: the verdicts per model.
    std::map<std::string, std::map<double, int>> shipped;  // model -> duty -> stabilized
    {
      std::ifstream in(std::string(PRONK_SOURCE_DIR) + "/results/map_seed_duty/trials.csv");
      std::string line;
      std::getline(in, line);
      std::vector<std::string> head;
      for (std::stringstream h(line); std::getline(h, line, ',');) head.push_back(line);
      auto col = [&](const std::string& n) {
        return static_cast<size_t>(std::find(head.begin(), head.end(), n) - head.begin());
      };
      while (std::getline(in, line)) {
        std::vector<std::string> f;
        for (std::stringstream r(line); std::getline(r, line, ',');) f.push_back(line);
        const double duty = std::stod(f[col("duty_cycle")]);
        if (std::stod(f[col("tilt_deg")]) != 0.0 || std::stol(f[col("trial")]) >= 8) continue;
        for (const std::string m : {"impulse", "pulse"})
          shipped[m][std::round(duty * 100) / 100] += f[col(m + "_stabilized")] == "1" ? 1 : 0;
      }
    }
    REQUIRE(shipped["pulse"].size() == 41);
    std::map<std::string, json> by;
    for (const auto& r : rb["rungs"]) by[r["model"].get<std::string>()] = r;
    REQUIRE(by.size() == 4);  // impulse, pulse, rigid, pseudo_rigid (the last two: not --quick)
    for (const std::string m : {"impulse", "pulse"}) {
      INFO(m);
      REQUIRE(by[m]["available"] == true);
      REQUIRE(by[m]["cells"].size() == 4);
      long only_this = 0, only_pulse = 0;
      for (const auto& c : by[m]["cells"]) {
        const double duty = c["duty"].get<double>();
        INFO("duty " << duty);
        CHECK(c["trials"] == 8);
        CHECK(c["stabilized"].get<int>() == shipped[m][duty]);
        CHECK(c["stabilized_fraction"].get<double>() == c["stabilized"].get<double>() / 8.0);
        only_this += c["only_this"].get<long>();
        only_pulse += c["only_pulse"].get<long>();
      }
      CHECK(by[m]["disagreements_vs_pulse"].get<long>() == only_this + only_pulse);
    }
    // The seed's finding: the impulse model stabilizes every trial, the pulse model loses
    // some from ~30 % duty; each such trial is a disagreement, and none goes the other way.
    CHECK(by["impulse"]["boundary_status"] == "all_good");
    long pulse_lost = 0;
    for (const auto& c : by["pulse"]["cells"]) pulse_lost += 8 - c["stabilized"].get<long>();
    CHECK(by["impulse"]["disagreements_vs_pulse"].get<long>() == pulse_lost);
    CHECK(by["pulse"]["disagreements_vs_pulse"] == 0);
    // Pulse boundary: bisected between its last all-stabilized duty and the next, with a
    // bracket no wider than the resolution. The shipped map (16 trials) has every trial
    // stabilized at every duty up to 0.28 and at 0.2875: so do its first 8, and this
    // bisection (0.25, 0.275, 0.2875) cannot end lower.
    const json& p = by["pulse"];
    CHECK(p["boundary_status"] == "bisected");
    CHECK(p["bracket_bad"].get<double>() - p["boundary"].get<double>() <=
          rb["boundary_resolution"].get<double>());
    CHECK(p["boundary"].get<double>() >= 0.2875 - 1e-12);
    CHECK(p["boundary"].get<double>() < 0.3);
    // Undisturbed gait of the pulse rung: stable (radius < 1) at every duty of the grid.
    for (const auto& c : p["cells"]) CHECK(c["spectral_radius"].get<double>() < 1.0);
    CHECK(by["pseudo_rigid"]["available"] == false);
  }

  SECTION("quad hopper drop: the energy balance holds and the feet land plastically") {
    // Independent reference for the first bounce: the feet (4 x 10 g) hit the ground
    // at v = sqrt(2 g h) and the critically damped contact stops them, so the first
    // bounce loses about their kinetic energy, 4 m_f g h, of the drop energy M g h.
    const double feet_share = 4 * 0.01 / 1.54;
    REQUIRE_FALSE(doc["quad_hopper_drop"].empty());
    for (const auto& r : doc["quad_hopper_drop"]) {
      INFO(r.dump());
      CHECK(r["status"] == "completed");
      // Hop to hop (at the flight apexes) the balance holds for every method; RODAS4 at
      // tol 1e-5 holds it everywhere (drift ~ tolerance); Verlet at h = 5e-4 s departs from
      // it inside impacts by its bounded term h^2 |F|^2 / 8m (measured 4.4e-2).
      CHECK(r["energy_error_apex_rel"].get<double>() < 1e-3);
      if (r["method"] == "verlet" && r["energy_tol"].get<double>() > 0.0) {
        // With energy_tol = 1e-4 of the energy scale (8.9 J = 3.9x the drop energy) every
        // sample stays within the budget plus the switching offset.
        CHECK(r["energy_error_rel"].get<double>() < 1e-3);
      } else if (r["method"] == "verlet") {
        CHECK(r["energy_error_rel"].get<double>() < 0.1);
      } else {
        CHECK(r["energy_error_rel"].get<double>() < 1e-2);
      }
      // Apex heights against RODAS4 at tol 1e-8 (Verlet 5e-4 s: 4 % of the drop, measured).
      CHECK(r["apex_height_vs_reference_rel"].get<double>() >= 0.0);
      CHECK(r["apex_height_vs_reference_rel"].get<double>() < 0.06);
      REQUIRE(r["bounces"].get<int>() >= 2);
      const double loss = r["first_bounce_energy_loss_rel"].get<double>();
      CHECK(loss > 0.5 * feet_share);
      CHECK(loss < 2.0 * feet_share);
      // Passive: no apex above the release height.
      for (const auto& a : r["apex_heights_m"]) CHECK(a.get<double>() < 0.44);
    }
  }

  SECTION("peers, when built, integrate the same problem to the same answer") {
    const json& cv = doc["peers"]["cvode"];
    if (cv["available"] == true) {
      for (const auto& p : cv["satellite"]) {
        INFO(p.dump());
        CHECK(p["status"] == "completed");
        CHECK(p["omega_final"].get<double>() < 1e-4);
        CHECK(p["steps"].get<long>() > 0);
      }
      CHECK(doc["headline"]["satellite"]["cvode_over_rodas4"].get<double>() > 0);
      // The quad hopper drop from the same mechanism file: completes and bounces (its
      // energy-balance accuracy is what the bench measures).
      REQUIRE(cv.contains("quad_hopper"));
      for (const auto& p : cv["quad_hopper"]) {
        INFO(p.dump());
        CHECK(p["status"] == "completed");
        CHECK(p["bounces"].get<int>() >= 1);
        CHECK(std::isfinite(p["energy_error_rel"].get<double>()));
      }
    }
    const json& mj = doc["peers"]["mujoco"];
    if (mj["available"] == true) {
      for (const auto& p : mj["runs"]) {
        CHECK(p["status"] == "completed");
        CHECK(p["bounces"].get<int>() >= 1);
        // MuJoCo's soft contact dissipates: energy never grows by more than a step's error.
        CHECK(p["first_bounce_energy_loss_rel"].get<double>() > -0.01);
      }
    }
  }
}

TEST_CASE("pronk bench: bad input exits 2 with a clear message", "[cli][bench]") {
  TempDir dir("bench");
  Run r = pronk(dir, {"bench", "--repeat", "0"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--repeat"));
  r = pronk(dir, {"bench", "--quick", "--studies", dir / "nowhere"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("case3_legged_pulse.json"));
  r = pronk(dir, {"bench", "--frobnicate"});
  CHECK(r.code == 2);
  std::ofstream(dir / "file") << "x";
  r = pronk(dir, {"bench", "--quick", "--out", dir / "file/sub"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--out"));
}
