// The diagrams of `pronk bench` (SVG through gnuplot, with the .gp scripts that hold their
// data): work-precision, stiffness, quad hopper drop, fixed-step convergence, robustness.
#include "app/bench/figures.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/write/figure_batch.hpp"

namespace pronk::app::bench {

namespace {

/// One curve of a diagram: (x, y) pairs.
struct Series {
  std::string title;
  std::vector<std::pair<double, double>> xy;
};

/// A log-log gnuplot script with the data inline ($d0 << EOD ...), so the .gp
/// alone reproduces the figure.
std::string loglog_script(const std::string& name, const std::string& title,
                          const std::string& xlabel, const std::string& ylabel,
                          const std::vector<Series>& series) {
  std::string s =
      "set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'\n"
      "set output '" +
      name + ".svg'\nset title '" + title + "'\nset xlabel '" + xlabel + "'\nset ylabel '" +
      ylabel +
      "'\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
      "set grid\nset key outside right\n";
  std::string plot = "plot ";
  int i = 0;
  for (const auto& se : series) {
    if (se.xy.empty()) continue;
    s += "$d" + std::to_string(i) + " << EOD\n";
    for (const auto& [x, y] : se.xy) s += fmt(x) + " " + fmt(y) + "\n";
    s += "EOD\n";
    plot += std::string(i ? ", " : "") + "$d" + std::to_string(i) +
            " using 1:2 with linespoints title '" + se.title + "' noenhanced";
    ++i;
  }
  if (i == 0) return "";
  return s + plot + "\n";
}

/// Work-precision series: error `err` vs wall time per (solver, variant) of `problem`.
std::vector<Series> wp_series(const std::vector<WorkPoint>& pts, const std::string& problem,
                              const std::string& err) {
  std::map<std::string, Series> by;
  for (const auto& p : pts) {
    if (p.problem != problem || p.status != "completed") continue;
    auto it = p.errors.find(err);
    if (it == p.errors.end() || !(it->second > 0) || !(p.cost.cpu_s > 0)) continue;
    const std::string key = p.solver + (p.variant.empty() ? "" : " (" + p.variant + " norm)");
    by[key].title = key;
    by[key].xy.push_back({p.cost.cpu_s, it->second});
  }
  std::vector<Series> out;
  for (auto& [k, v] : by) out.push_back(v);
  return out;
}

/// Stabilized fraction vs duty per rung (linear axes), the boundaries as vertical marks.
std::string robustness_script(const LadderRobustness& lr) {
  std::string s =
      "set terminal svg size 900,560 dynamic enhanced font 'Helvetica,11'\n"
      "set output 'fidelity_robustness.svg'\n"
      "set title 'Fidelity ladder: fraction of " +
      std::to_string(lr.trials) +
      " seeded disturbance trials stabilized (map_seed_duty, row 0)' noenhanced\n"
      "set xlabel 'duty cycle [-]'\nset ylabel 'stabilized fraction [-]'\n"
      "set yrange [-0.05:1.05]\nset offsets 0.05, 0.05, 0, 0\nset grid\n"
      "set key outside right\n";
  std::string plot = "plot ";
  int i = 0;
  for (const auto& r : lr.rungs) {
    if (!r.available || r.cells.empty()) continue;
    s += "$d" + std::to_string(i) + " << EOD\n";
    for (const auto& c : r.cells) s += fmt(c.duty) + " " + fmt(c.fraction) + "\n";
    s += "EOD\n";
    plot += std::string(i ? ", " : "") + "$d" + std::to_string(i) +
            // Rungs that agree draw on top of each other: distinct points, widths and dashes.
            " using 1:2 with linespoints lw " + std::to_string(3 - i) + " dt " +
            std::to_string(i + 1) + " pt " + std::to_string(4 + 2 * i) + " ps 1.5 title '" +
            r.model + " (boundary " + r.boundary_status + " " + fmt(r.boundary) + ")' noenhanced";
    ++i;
  }
  if (i == 0) return "";
  return s + plot + "\n";
}

std::vector<Series> series_list(std::map<std::string, Series>& by) {
  std::vector<Series> s;
  for (auto& [k, v] : by) s.push_back(v);
  return s;
}

/// The work-precision diagrams of the satellite and the hopper.
void write_work_precision_figures(const std::string& dir, const BenchResults& r,
                                  io::FigureBatch& figures) {
  auto sat_series = wp_series(r.sat, "satellite", "omega_final");
  if (r.cvode.value("available", false)) {
    std::map<std::string, Series> by;
    for (const auto& x : r.cvode["satellite"]) {
      if (x["status"] != "completed") continue;
      const std::string key = "CVODE BDF (" + x["variant"].get<std::string>() + ")";
      by[key].title = key;
      by[key].xy.push_back({x["cpu_s"].get<double>(), x["omega_final"].get<double>()});
    }
    for (auto& [k, v] : by) sat_series.push_back(v);
  }
  const std::vector<std::pair<std::string, std::string>> figs = {
      {"satellite_work_precision",
       loglog_script("satellite_work_precision",
                     "Satellite (k = 1e6 N/m, 20 s): omega error vs CPU time", "CPU time [s]",
                     "relative omega error at 20 s", sat_series)},
      {"hopper_work_precision",
       loglog_script("hopper_work_precision",
                     "Reduced legged pulse hopper: final CoM error vs CPU time", "CPU time [s]",
                     "final CoM position error [m]", wp_series(r.hop, "hopper", "final_state"))},
  };
  for (const auto& [name, script] : figs) {
    if (!script.empty()) figures.add(dir, name, script);
  }
}

/// Stiffness sweep: wall time vs k.
void write_stiffness_figure(const std::string& dir, const BenchResults& r,
                            io::FigureBatch& figures) {
  std::map<std::string, Series> by;
  for (const auto& p : r.sweep) {
    if (p.status != "completed") continue;
    const std::string key = p.solver + " (" + p.variant + " norm)";
    by[key].title = key;
    by[key].xy.push_back({p.stiffness, p.cost.cpu_s});
  }
  if (r.cvode.value("available", false)) {
    for (const auto& x : r.cvode["stiffness"]) {
      if (x["status"] != "completed") continue;
      const std::string key = "CVODE BDF (" + x["variant"].get<std::string>() + ")";
      by[key].title = key;
      by[key].xy.push_back({x["stiffness"].get<double>(), x["cpu_s"].get<double>()});
    }
  }
  const std::string script =
      loglog_script("satellite_stiffness", "Satellite, tol 1e-6: CPU time vs internal stiffness",
                    "internal stiffness [N/m]", "CPU time [s]", series_list(by));
  if (!script.empty()) figures.add(dir, "satellite_stiffness", script);
}

/// Quad hopper drop: energy error vs cost per simulated second, pronk and MuJoCo.
void write_drop_figure(const std::string& dir, const BenchResults& r, io::FigureBatch& figures) {
  std::map<std::string, Series> by;
  for (const auto& x : r.drop) {
    if (x["status"] != "completed") continue;
    std::string key = x.value("method", "rodas4") == "verlet"
                          ? std::string("pronk Verlet")
                          : "pronk RODAS4 (" + x["norm"].get<std::string>() + " norm)";
    if (x.value("body", "four_masses") == "rigid") key += ", rigid body";
    by[key].title = key;
    by[key].xy.push_back(
        {x["cost_per_sim_s"].get<double>(), std::max(1e-12, x["energy_error_rel"].get<double>())});
  }
  if (r.mujoco.value("available", false)) {
    for (const auto& x : r.mujoco["runs"]) {
      if (x["status"] != "completed") continue;
      const std::string key = "MuJoCo " + x["integrator"].get<std::string>();
      by[key].title = key;
      by[key].xy.push_back({x["cost_per_sim_s"].get<double>(),
                            std::max(1e-12, std::abs(x["total_energy_loss_rel"].get<double>()))});
    }
  }
  const std::string script = loglog_script(
      "quad_hopper_work_precision", "Quad spring hopper drop: energy error vs cost",
      "CPU time per simulated second [s/s]", "energy error / drop energy", series_list(by));
  if (!script.empty()) figures.add(dir, "quad_hopper_work_precision", script);
}

/// Fixed-step convergence on the hopper.
void write_convergence_figure(const std::string& dir, const BenchResults& r,
                              io::FigureBatch& figures) {
  std::map<std::string, Series> by;
  for (const auto& p : r.hop) {
    if (p.problem != "hopper" || p.h <= 0 || p.status != "completed") continue;
    by[p.solver].title = p.solver;
    by[p.solver].xy.push_back({p.h, p.errors.at("final_state")});
  }
  const std::string script =
      loglog_script("hopper_convergence", "Fixed-step methods on the hopper: error vs step",
                    "step h [s]", "final CoM position error [m]", series_list(by));
  if (!script.empty()) figures.add(dir, "hopper_convergence", script);
}

}  // namespace

void write_bench_figures(const std::string& dir, const BenchResults& r) {
  io::FigureBatch figures;
  write_work_precision_figures(dir, r, figures);
  if (const std::string script = robustness_script(r.robustness); !script.empty())
    figures.add(dir, "fidelity_robustness", script);
  write_stiffness_figure(dir, r, figures);
  write_drop_figure(dir, r, figures);
  write_convergence_figure(dir, r, figures);
  figures.finish();
}

}  // namespace pronk::app::bench
