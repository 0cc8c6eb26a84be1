// The records of `pronk bench` as bench.json and the CSV tables.
#include "app/bench/report.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#include "app/bench/headline.hpp"
#include "io/build_info.hpp"

namespace pronk::app::bench {

using nlohmann::json;

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

json to_json(const WorkPoint& p) {
  json j = {{"problem", p.problem},     {"solver", p.solver}, {"variant", p.variant},
            {"stiffness", p.stiffness}, {"tol", p.tol},       {"h", p.h},
            {"t_end", p.t_end},         {"status", p.status}, {"errors", json::object()}};
  add_cost(j, p.cost);
  for (const auto& [k, v] : p.errors) {
    if (std::isfinite(v)) j["errors"][k] = v;
  }
  return j;
}

json to_json(const FidelityPoint& p) {
  return {{"model", p.model},
          {"available", p.available},
          {"note", p.note},
          {"pulse_duration", p.pulse_duration},
          {"status", p.status},
          {"t_end", p.t_end},
          {"wall_s", p.wall_s},
          {"cpu_s", p.cpu_s},
          {"cost_per_sim_s", p.cost_per_sim_s},
          {"ran_model", p.ran_model},
          {"rhs_evaluations", p.rhs_evaluations},
          {"jacobians", p.jacobians},
          {"strides", p.strides},
          {"mean_duty", p.mean_duty},
          {"mean_apex_m", p.mean_apex},
          {"apex_rms_vs_impulse_m", p.apex_rms_vs_impulse},
          {"spectral_radius", p.spectral_radius},
          {"spectral_radius_method", p.spectral_radius_method},
          {"spectral_radius_fit", p.spectral_radius_fit},
          {"fit_ok", p.fit_ok},
          {"fit_residual_rel", p.fit_residual_rel},
          {"stable", p.stable},
          {"fixed_point_vs_impulse", p.fixed_point_vs_impulse},
          {"apex_max_vs_four_mass_m", p.apex_max_vs_four_mass}};
}

json to_json(const LadderRobustness& lr) {
  json rungs = json::array();
  for (const auto& r : lr.rungs) {
    json cells = json::array();
    for (const auto& c : r.cells) {
      cells.push_back({{"duty", c.duty},
                       {"trials", c.trials},
                       {"stabilized", c.stabilized},
                       {"stabilized_fraction", c.fraction},
                       {"fell", c.fell},
                       {"mean_duty", c.mean_duty},
                       {"spectral_radius", c.spectral_radius},
                       {"only_this", c.only_this},
                       {"only_pulse", c.only_pulse}});
    }
    json j = {{"model", r.model}, {"available", r.available}, {"note", r.note}, {"cells", cells}};
    if (r.available) {
      j["boundary_status"] = r.boundary_status;
      j["boundary"] = r.boundary;
      j["bracket_bad"] = r.bad;
      j["first_good"] = r.first_good;
      j["probes"] = r.probes;
      j["disagreements_vs_pulse"] = r.disagreements_vs_pulse;
      j["cpu_s"] = r.cpu_s;
    }
    rungs.push_back(j);
  }
  return {{"study", lr.study},
          {"trials_per_cell", lr.trials},
          {"seed", lr.seed},
          {"trial_duration_s", lr.trial_duration},
          {"duties", lr.duties},
          {"boundary_resolution", lr.resolution},
          {"definitions",
           {{"stabilized",
             "pronk map's: no fall, settled (position, tilt, apex) by stride 30 and "
             "held for 3 strides to the end of the trial"},
            {"boundary",
             "largest duty at which every trial stabilizes: the last good cell, bisected "
             "towards the next until the bracket [boundary, bracket_bad] is at most "
             "boundary_resolution wide (status all_good: >= the last duty; none_good: < the "
             "first)"},
            {"disagreements_vs_pulse",
             "trials this rung stabilizes and the pulse rung does not (only_this) or the "
             "reverse (only_pulse), same trials"},
            {"spectral_radius",
             "undisturbed gait at the duty: stride map (impulse, pulse), fitted estimate "
             "(rigid, pseudo_rigid); 10 = no orbit / no estimate"}}},
          {"rungs", rungs}};
}

/// bench.json's "auto_check": per scene auto against the fastest run at the same accuracy.
json auto_check_json(const std::vector<AutoCheck>& autos) {
  json j = {{"target_ratio", kAutoRatioTarget}, {"scenes", json::array()}};
  bool all = !autos.empty();
  for (const auto& a : autos) {
    j["scenes"].push_back(to_json(a));
    all = all && a.within;
  }
  j["all_within"] = all;
  return j;
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return b;
}

std::string machine() {
  std::string cpu = "unknown CPU";
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  return cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

/// bench.json without its total wall time.
json bench_document(const BenchConfig& c, const BenchResults& r,
                    const std::vector<WorkPoint>& all) {
  json doc;
  doc["benchmark"] = "pronk bench";
  doc["version"] = pronk::version();
  doc["commit"] = pronk::git_commit();
  doc["date_utc"] = now_utc();
  doc["machine"] = machine();
  doc["quick"] = c.quick;
  doc["repeat"] = c.repeat;
  doc["work_precision"] = json::array();
  for (const auto& p : all) doc["work_precision"].push_back(to_json(p));
  doc["orders"] = json::array();
  for (const auto& o : r.orders) {
    doc["orders"].push_back({{"problem", o.problem},
                             {"solver", o.solver},
                             {"error", o.error},
                             {"order", o.order},
                             {"points", o.points}});
  }
  doc["fidelity_ladder"] = json::array();
  for (const auto& p : r.ladder) doc["fidelity_ladder"].push_back(to_json(p));
  doc["fidelity_robustness"] = to_json(r.robustness);
  doc["quad_hopper_drop"] = r.drop;
  doc["peers"]["cvode"] = r.cvode;
  doc["peers"]["mujoco"] = r.mujoco;
  doc["auto_check"] = auto_check_json(r.autos);
  doc["headline"] = headline(r.sat, r.sweep, r.drop, r.cvode, r.mujoco);
  return doc;
}

std::string work_precision_csv(const std::vector<WorkPoint>& pts) {
  const std::array<const char*, 7> errs = {"omega_final",    "omega_l2",       "final_state",
                                           "l2_series",      "touchdown_time", "fixed_point",
                                           "spectral_radius"};
  std::string s =
      "problem,solver,variant,stiffness,tol,h,t_end,status,wall_s,cpu_s,steps,rejected,rhs,"
      "jacobians,lu";
  for (const char* e : errs) s += std::string(",err_") + e;
  s += "\n";
  for (const auto& p : pts) {
    s += p.problem + "," + p.solver + "," + p.variant + "," + fmt(p.stiffness) + "," + fmt(p.tol) +
         "," + fmt(p.h) + "," + fmt(p.t_end) + "," + p.status + "," + fmt(p.cost.wall_s) + "," +
         fmt(p.cost.cpu_s) + "," + std::to_string(p.cost.steps) + "," +
         std::to_string(p.cost.rejected) + "," + std::to_string(p.cost.rhs) + "," +
         std::to_string(p.cost.jacobians) + "," + std::to_string(p.cost.lu);
    for (const char* e : errs) {
      auto it = p.errors.find(e);
      s += ",";
      if (it != p.errors.end()) s += fmt(it->second);
    }
    s += "\n";
  }
  return s;
}

std::string ladder_csv(const std::vector<FidelityPoint>& pts) {
  std::string s =
      "model,available,pulse_duration,status,t_end,wall_s,cpu_s,cost_per_sim_s,strides,mean_duty,"
      "mean_apex_m,apex_rms_vs_impulse_m,spectral_radius,spectral_radius_method,"
      "spectral_radius_fit,fit_ok,stable,fixed_point_vs_impulse,apex_max_vs_four_mass_m,note\n";
  for (const auto& p : pts) {
    s += p.model + "," + (p.available ? "1" : "0") + "," + fmt(p.pulse_duration) + "," + p.status +
         "," + fmt(p.t_end) + "," + fmt(p.wall_s) + "," + fmt(p.cpu_s) + "," +
         fmt(p.cost_per_sim_s) + "," + std::to_string(p.strides) + "," + fmt(p.mean_duty) + "," +
         fmt(p.mean_apex) + "," + fmt(p.apex_rms_vs_impulse) + "," + fmt(p.spectral_radius) + "," +
         p.spectral_radius_method + "," + fmt(p.spectral_radius_fit) + "," +
         (p.fit_ok ? "1" : "0") + "," + (p.stable ? "1" : "0") + "," +
         fmt(p.fixed_point_vs_impulse) + "," + fmt(p.apex_max_vs_four_mass) + ",\"" + p.note +
         "\"\n";
  }
  return s;
}

std::string robustness_csv(const LadderRobustness& lr) {
  std::string s =
      "model,duty,trials,stabilized,stabilized_fraction,fell,mean_duty,spectral_radius,only_this,"
      "only_pulse,boundary_status,boundary,disagreements_vs_pulse\n";
  for (const auto& r : lr.rungs) {
    if (!r.available) {
      s += r.model + ",,,,,,,,,,not_available,,\n";
      continue;
    }
    for (const auto& c : r.cells) {
      s += r.model + "," + fmt(c.duty) + "," + std::to_string(c.trials) + "," +
           std::to_string(c.stabilized) + "," + fmt(c.fraction) + "," + std::to_string(c.fell) +
           "," + fmt(c.mean_duty) + "," + fmt(c.spectral_radius) + "," +
           std::to_string(c.only_this) + "," + std::to_string(c.only_pulse) + "," +
           r.boundary_status + "," + fmt(r.boundary) + "," +
           std::to_string(r.disagreements_vs_pulse) + "\n";
    }
  }
  return s;
}

}  // namespace pronk::app::bench
