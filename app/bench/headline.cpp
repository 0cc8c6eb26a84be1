// The headline of `pronk bench`: the ratios against the targets of issues 3, 4 and 7.
#include "app/bench/headline.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace pronk::app {

using bench::WorkPoint;
using nlohmann::json;

namespace bench_headline {

/// Fastest wall time among `pts` of `problem`/`solver` whose omega_final <= limit.
const WorkPoint* fastest_within(const std::vector<WorkPoint>& pts, const std::string& problem,
                                const std::string& solver, double stiffness, double limit) {
  const WorkPoint* best = nullptr;
  for (const auto& p : pts) {
    if (p.problem != problem || p.solver != solver || p.stiffness != stiffness) continue;
    auto it = p.errors.find("omega_final");
    if (p.status != "completed" || it == p.errors.end() || it->second > limit) continue;
    if (!best || p.cost.cpu_s < best->cost.cpu_s) best = &p;
  }
  return best;
}

const WorkPoint* find_point(const std::vector<WorkPoint>& pts, const std::string& problem,
                            const std::string& solver, const std::string& variant, double k) {
  for (const auto& p : pts) {
    if (p.problem == problem && p.solver == solver && p.variant == variant && p.stiffness == k) {
      return &p;
    }
  }
  return nullptr;
}

json point_brief(const WorkPoint* p) {
  if (!p) return {{"found", false}};
  json j = {{"solver", p->solver},      {"variant", p->variant},  {"tol", p->tol},
            {"wall_s", p->cost.wall_s}, {"cpu_s", p->cost.cpu_s}, {"steps", p->cost.steps},
            {"rhs", p->cost.rhs}};
  if (p->errors.count("omega_final")) j["omega_final"] = p->errors.at("omega_final");
  return j;
}

/// Issue 3: the satellite within an omega error limit, pronk's solvers and CVODE.
void satellite(const std::vector<WorkPoint>& sat, const json& cvode, json* out) {
  json& h = *out;
  const double limit = 1e-5;
  const WorkPoint* rodas = fastest_within(sat, "satellite", "rodas4", 1e6, limit);
  const WorkPoint* dopri = fastest_within(sat, "satellite", "dopri5", 1e6, limit);
  h["satellite"]["omega_error_limit"] = limit;
  h["satellite"]["rodas4"] = point_brief(rodas);
  h["satellite"]["dopri5"] = point_brief(dopri);
  if (rodas && dopri) h["satellite"]["dopri5_over_rodas4"] = dopri->cost.cpu_s / rodas->cost.cpu_s;
  h["satellite"]["anchor_cvode_issue3_s"] = 0.35;
  if (rodas) h["satellite"]["anchor_over_rodas4"] = 0.35 / rodas->cost.cpu_s;
  // Issue 23: pronk's fastest stiff method (RODAS4, RADAU5, its CVODE backend) within the limit.
  const WorkPoint* best_stiff = nullptr;
  for (const char* solver : {"rodas4", "radau5", "cvode_bdf"}) {
    const WorkPoint* p = fastest_within(sat, "satellite", solver, 1e6, limit);
    if (p && (!best_stiff || p->cost.cpu_s < best_stiff->cost.cpu_s)) best_stiff = p;
  }
  h["satellite"]["best_stiff"] = point_brief(best_stiff);
  h["satellite"]["radau5"] = point_brief(fastest_within(sat, "satellite", "radau5", 1e6, limit));
  h["satellite"]["pronk_cvode_bdf"] =
      point_brief(fastest_within(sat, "satellite", "cvode_bdf", 1e6, limit));
  // The fastest pronk setting of any solver within the limit (issue 3's target is pronk's).
  const WorkPoint* fastest = nullptr;
  for (const char* solver : {"rodas4", "radau5", "cvode_bdf", "dopri5", "rk4", "verlet"}) {
    const WorkPoint* p = fastest_within(sat, "satellite", solver, 1e6, limit);
    if (p && (!fastest || p->cost.cpu_s < fastest->cost.cpu_s)) fastest = p;
  }
  h["satellite"]["fastest"] = point_brief(fastest);
  if (fastest) {
    h["satellite"]["fastest"]["h"] = fastest->h;
    h["satellite"]["anchor_over_fastest"] = 0.35 / fastest->cost.cpu_s;
  }
  if (cvode.value("available", false) && rodas) {
    double best = -1;
    json best_run;
    for (const auto& r : cvode["satellite"]) {
      if (r.value("status", "") != "completed" || r["omega_final"].get<double>() > limit) continue;
      if (best < 0 || r["cpu_s"].get<double>() < best) {
        best = r["cpu_s"];
        best_run = r;
      }
    }
    if (best > 0) {
      h["satellite"]["cvode"] = best_run;
      h["satellite"]["cvode_over_rodas4"] = best / rodas->cost.cpu_s;
      h["satellite"]["target_cvode_over_rodas4"] = 10.0;
      if (fastest) h["satellite"]["cvode_over_fastest"] = best / fastest->cost.cpu_s;
      if (best_stiff) {
        h["satellite"]["cvode_over_best_stiff"] = best / best_stiff->cost.cpu_s;
        h["satellite"]["target_cvode_over_best_stiff"] = 1.0;
      }
    }
  }
}

/// The per-stiffness points (null: none within the limit) and, when both ends have one, the
/// cost ratio 1e8 / 1e4 and the largest over the smallest cost of the sweep.
json growth_of(const std::map<double, const WorkPoint*>& by_k) {
  json g;
  g["points"] = json::array();
  double lo = -1, hi = -1, mn = -1, mx = -1;
  bool all = true;
  for (const auto& [k, p] : by_k) {
    if (!p) {
      g["points"].push_back({{"stiffness", k}, {"found", false}});
      all = false;
      continue;
    }
    json b = point_brief(p);
    b["stiffness"] = k;
    b["omega_final_ref"] = p->errors.at("omega_final_ref");
    const auto model = p->errors.find("model_omega_error");
    if (model != p->errors.end()) b["model_omega_error"] = model->second;
    if (p->h > 0) b["h"] = p->h;
    g["points"].push_back(b);
    if (k == 1e4) lo = p->cost.cpu_s;
    if (k == 1e8) hi = p->cost.cpu_s;
    mn = mn < 0 ? p->cost.cpu_s : std::min(mn, p->cost.cpu_s);
    mx = std::max(mx, p->cost.cpu_s);
  }
  if (lo > 0 && hi > 0) g["ratio"] = hi / lo;
  if (all && mn > 0) g["max_over_min"] = mx / mn;
  return g;
}

/// Issue 23: per solver (and norm), the cheapest sweep point at each stiffness whose omega
/// error against the tight reference of that stiffness (the model's own solution) is within
/// the target, and the growth of its cost from 1e4 to 1e8 N/m; "best_stiff" takes the
/// cheapest stiff method (RODAS4 either norm, RADAU5) at each stiffness. The target is 1e-5,
/// or the model's own omega error at that stiffness where that is larger (`with_model_error`:
/// a solver need not be more accurate than the model it integrates; at 1e4 N/m the model is
/// 1.4e-4 off the rigid body), else 1e-5 everywhere.
json matched_growth(const std::vector<WorkPoint>& sweep, bool with_model_error) {
  const double target = 1e-5;
  auto limit_of = [&](const WorkPoint& p) {
    const auto it = p.errors.find("model_omega_error");
    return with_model_error && it != p.errors.end() ? std::max(target, it->second) : target;
  };
  const std::vector<std::pair<std::string, std::string>> kinds = {{"rodas4", "state"},
                                                                  {"rodas4", "body"},
                                                                  {"dopri5", "state"},
                                                                  {"radau5", "state"},
                                                                  {"verlet", "state"}};
  json m;
  m["omega_error_vs_reference_limit"] = target;
  m["limit_includes_model_error"] = with_model_error;
  std::map<double, const WorkPoint*> best_stiff;
  for (const auto& [solver, variant] : kinds) {
    std::map<double, const WorkPoint*> cheapest;
    for (const auto& p : sweep) {
      if (p.problem != "satellite_stiffness" || p.solver != solver || p.variant != variant) {
        continue;
      }
      cheapest.emplace(p.stiffness, nullptr);
      auto it = p.errors.find("omega_final_ref");
      if (p.status != "completed" || it == p.errors.end() || it->second > limit_of(p)) continue;
      const WorkPoint*& c = cheapest[p.stiffness];
      if (!c || p.cost.cpu_s < c->cost.cpu_s) c = &p;
      if (solver != "dopri5" && solver != "verlet") {
        const WorkPoint*& b = best_stiff[p.stiffness];
        if (!b || p.cost.cpu_s < b->cost.cpu_s) b = &p;
      }
    }
    if (cheapest.empty()) continue;
    m[solver + "_" + variant] = growth_of(cheapest);
  }
  if (!best_stiff.empty()) m["best_stiff"] = growth_of(best_stiff);
  return m;
}

/// Issue 7: CPU time growth from k = 1e4 to 1e8 N/m.
void stiffness_growth(const std::vector<WorkPoint>& sweep, const json& cvode, json* out) {
  json& h = *out;
  h["stiffness_growth"]["matched"] = matched_growth(sweep, true);
  h["stiffness_growth"]["matched_strict"] = matched_growth(sweep, false);
  for (const std::string v : {"state", "body"}) {
    const WorkPoint* lo = find_point(sweep, "satellite_stiffness", "rodas4", v, 1e4);
    const WorkPoint* hi = find_point(sweep, "satellite_stiffness", "rodas4", v, 1e8);
    if (lo && hi && lo->cost.cpu_s > 0) {
      h["stiffness_growth"]["rodas4_" + v + "_norm"] = {
          {"cpu_1e4_s", lo->cost.cpu_s},
          {"cpu_1e8_s", hi->cost.cpu_s},
          {"ratio", hi->cost.cpu_s / lo->cost.cpu_s},
          {"steps_ratio", static_cast<double>(hi->cost.steps) / std::max(1L, lo->cost.steps)}};
    }
  }
  for (const char* solver : {"radau5", "verlet"}) {
    const WorkPoint* lo = nullptr;
    const WorkPoint* hi = nullptr;
    for (const auto& p : sweep) {
      if (p.problem != "satellite_stiffness" || p.solver != solver) continue;
      if (std::string(solver) == "radau5" && p.tol != 1e-8) continue;  // the fixed-tol row
      if (p.stiffness == 1e4) lo = &p;
      if (p.stiffness == 1e8) hi = &p;
    }
    if (lo && hi && lo->cost.cpu_s > 0) {
      h["stiffness_growth"][solver] = {
          {"cpu_1e4_s", lo->cost.cpu_s},
          {"cpu_1e8_s", hi->cost.cpu_s},
          {"ratio", hi->cost.cpu_s / lo->cost.cpu_s},
          {"steps_ratio", static_cast<double>(hi->cost.steps) / std::max(1L, lo->cost.steps)}};
    }
  }
  h["stiffness_growth"]["target_ratio"] = 3.0;
  if (cvode.value("available", false) && cvode.contains("stiffness")) {
    double lo = -1, hi = -1;
    for (const auto& r : cvode["stiffness"]) {
      if (r["variant"] != "dense_analytic") continue;
      if (r["stiffness"].get<double>() == 1e4) lo = r["cpu_s"];
      if (r["stiffness"].get<double>() == 1e8) hi = r["cpu_s"];
    }
    if (lo > 0 && hi > 0) h["stiffness_growth"]["cvode_dense_analytic"] = {{"ratio", hi / lo}};
  }
}

/// Issue 4: the quad hopper drop against MuJoCo Euler at 1 ms.
void quad_hopper(const json& drop, const json& mujoco, json* out) {
  json& h = *out;
  // Quad hopper: the fastest pronk run with energy-balance drift <= 1e-3 of the drop
  // energy (issue 4) vs MuJoCo Euler at 1 ms, per simulated second; the drift taken at
  // every sample ("energy_error_rel") or at the flight apexes, hop to hop
  // ("energy_error_apex_rel": it leaves out a fixed-step method's bounded transient inside
  // impacts). Returns its CPU time [s] (-1: none) and the run.
  auto fastest_drop = [&drop](const char* error_field, json* run,
                              const char* body = "four_masses") {
    double best = -1;
    *run = {{"found", false}};
    for (const auto& r : drop) {
      if (r["status"] != "completed" || r[error_field].get<double>() > 1e-3) continue;
      if (r.value("body", "four_masses") != body) continue;
      if (best < 0 || r["cpu_s"].get<double>() < best) {
        best = r["cpu_s"];
        *run = r;
      }
    }
    return best;
  };
  json best_run, best_apex_run;
  const double best = fastest_drop("energy_error_rel", &best_run);
  const double best_apex = fastest_drop("energy_error_apex_rel", &best_apex_run);
  h["quad_hopper"]["pronk"] = best_run;
  h["quad_hopper"]["pronk_apex_balance"] = best_apex_run;
  // The same with the body as one rigid body (target: <= 0.5x MuJoCo Euler 1 ms).
  json best_rigid_run;
  const double best_rigid = fastest_drop("energy_error_rel", &best_rigid_run, "rigid");
  h["quad_hopper"]["pronk_rigid"] = best_rigid_run;
  h["quad_hopper"]["rigid_target_over_mujoco_euler_1ms"] = 0.5;
  h["quad_hopper"]["anchor_mujoco_euler_1ms_issue4_s"] = 0.041;
  if (mujoco.value("available", false)) {
    for (const auto& r : mujoco["runs"]) {
      if (r["integrator"] == "Euler" && r["timestep"].get<double>() == 1e-3) {
        h["quad_hopper"]["mujoco_euler_1ms"] = r;
        if (best > 0) {
          // Same simulated time on both sides (the peer scales to 10 s).
          const double pronk_per_s = best / best_run["t_end"].get<double>();
          h["quad_hopper"]["pronk_over_mujoco_euler_1ms"] =
              pronk_per_s / r["cost_per_sim_s"].get<double>();
        }
        if (best_rigid > 0) {
          h["quad_hopper"]["pronk_rigid_over_mujoco_euler_1ms"] =
              best_rigid / best_rigid_run["t_end"].get<double>() /
              r["cost_per_sim_s"].get<double>();
        }
        if (best_apex > 0) {
          h["quad_hopper"]["pronk_apex_balance_over_mujoco_euler_1ms"] =
              best_apex / best_apex_run["t_end"].get<double>() / r["cost_per_sim_s"].get<double>();
        }
      }
    }
  }
}

}  // namespace bench_headline

json headline(const std::vector<WorkPoint>& sat, const std::vector<WorkPoint>& sweep,
              const json& drop, const json& cvode, const json& mujoco) {
  json h;
  bench_headline::satellite(sat, cvode, &h);
  bench_headline::stiffness_growth(sweep, cvode, &h);
  bench_headline::quad_hopper(drop, mujoco, &h);
  return h;
}

}  // namespace pronk::app
