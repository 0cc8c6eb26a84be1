#include "io/write/robot_output.hpp"

#include <cmath>

#include "io/load/robot_settings.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/method_choice_output.hpp"
#include "sim/mujoco/robot_mjcf.hpp"

namespace pronk::io {

using json = nlohmann::json;

namespace {

const char* kSvgHeader =
    "set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'\n"
    "set datafile separator ','\nset key autotitle columnhead\nset grid\n";

std::string figure_hop(size_t legs, bool feet) {
  std::string s = std::string(kSvgHeader) +
                  "set output 'hop_forces.svg'\nset multiplot layout 2,1\n"
                  "set title 'Hop height (CoM)'; set xlabel 'time [s]'; set ylabel 'z [m]'\n"
                  "plot 'trajectory.csv' u 1:4 w l t 'CoM z'\n"
                  "set title 'Leg actuator forces (+ pushes the body up)'; set ylabel 'force [N]'\n"
                  "plot ";
  for (size_t i = 0; i < legs; ++i) {
    s += (i ? ", " : "") + std::string("'feet.csv' u 1:") + std::to_string(2 + i) + " w l t 'leg " +
         std::to_string(i) + "'";
  }
  if (feet) {
    for (size_t i = 0; i < legs; ++i) {
      s += ", 'feet.csv' u 1:" + std::to_string(2 + legs + i) + " w l dt 2 t 'ground on foot " +
           std::to_string(i) + "'";
    }
  }
  return s + "\nunset multiplot\n";
}

std::string figure_energy() {
  return std::string(kSvgHeader) +
         "set output 'energy.svg'\n"
         "set title 'Energy by class'; set xlabel 'time [s]'; set ylabel 'energy [J]'\n"
         "plot 'energy.csv' u 1:2 w l t 'kinetic', '' u 1:3 w l t 'gravitational', "
         "'' u 1:4 w l t 'internal springs', '' u 1:5 w l t 'leg springs', '' u 1:6 w l t "
         "'contact', '' u 1:7 w l t 'dissipated', '' u 1:8 w l t 'actuator work', "
         "'' u 1:9 w l lw 2 t 'balance'\n";
}

std::string figure_path() {
  return std::string(kSvgHeader) +
         "set output 'path3d.svg'\n"
         "set title 'Path of the CoM'; set xlabel 'x [m]'; set ylabel 'y [m]'\n" +
         path3d_z_axis() +
         "splot 'trajectory.csv' u 2:3:4 w l t 'CoM', '' u 14:15:(0) w l dt 2 t 'setpoint'\n";
}

/// The settings the method ran with: its step for a fixed-step method (and Verlet's energy
/// budget), else its tolerances.
json solver_json(ode::Method method, double h_fixed, double energy_tol, double rtol, double atol) {
  json s = {{"method", std::string(ode::to_string(method))}};
  if (!ode::is_adaptive(method)) {
    s["h_fixed"] = h_fixed;
    if (method == ode::Method::kVerlet) s["energy_tol"] = energy_tol;
  } else {
    s["rtol"] = rtol;
    s["atol"] = atol;
  }
  return s;
}

}  // namespace

json robot_summary_json(const scene::Scene& scene, const robot::RobotRunResult& r,
                        const reduced::RunMetrics& metrics,
                        const robot::FidelityDiscrepancy* pulse) {
  json j = run_summary_json(scene, r.run, metrics);
  const auto& m = r.monitors;
  const auto& so = scene.pseudo_rigid.solver;
  j["solver"] = solver_json(so.method, so.h_fixed, scene.pseudo_rigid.energy_tol, so.rtol, so.atol);
  j["cost"]["jacobian_evaluations"] = r.run.cost.solver.jacobian_evaluations;
  j["cost"]["lu_factorizations"] = r.run.cost.solver.lu_factorizations;
  double max_slip_stance = 0.0;
  for (double s : r.stride_slip) max_slip_stance = std::max(max_slip_stance, s);
  const bool in_mujoco = scene.model == scene::ModelKind::kMujoco;
  if (in_mujoco) {
    j["solver"] = {{"engine", "mujoco"},
                   {"integrator", mujoco::integrator_name(scene.mujoco.integrator)},
                   {"timestep", scene.mujoco.timestep},
                   {"mj_step_cpu_s", r.engine_cpu}};
  }
  j["pseudo_rigid"] = {{"energy_scale_J", m.energy_scale},
                       {"energy_balance_drift_J", m.energy_drift},
                       {"energy_balance_drift_relative", m.drift_relative()},
                       {"max_strain", m.max_strain},
                       {"max_penetration_m", m.max_penetration},
                       {"max_slip_per_stance_m", max_slip_stance},
                       {"max_friction_ratio", m.max_friction_ratio},
                       {"hip_and_external_work_J", m.hip_work},
                       {"max_leg_vibration_energy_J", m.max_leg_vibration_energy},
                       {"zero_length_triggers", m.zero_length_triggers},
                       {"internal_stiffness_N_per_m", m.internal_stiffness},
                       {"contact_stiffness_N_per_m", m.contact_stiffness},
                       {"stiffness_note", m.stiffness.note}};
  if (in_mujoco) j["pseudo_rigid"]["energy_balance_monitored"] = false;
  if (m.method_auto) {
    const pseudorigid::MethodChoice& c = m.method_choice;
    j["solver"] = solver_json(c.method, c.h_fixed, c.energy_tol, c.rtol, c.atol);
    add_method_choice(c, m.drift_relative(), &j);
  }
  if (pulse != nullptr) {
    j["pseudo_rigid"]["discrepancy_vs_pulse_model"] = {
        {"strides_compared", pulse->strides},
        {"max_apex_difference_m", pulse->max_apex},
        {"max_touchdown_attitude_difference_deg", pulse->max_attitude * 180.0 / M_PI},
        {"max_touchdown_position_difference_m", pulse->max_touchdown_position}};
  }
  return j;
}

Table robot_energy_table(const robot::RobotRunResult& r) {
  Table t;
  t.columns = {"t",       "kinetic",    "gravitational", "internal", "leg",
               "contact", "dissipated", "actuator_work", "balance"};
  t.data.reserve(r.samples.size() * t.columns.size());
  for (const auto& s : r.samples) {
    const auto& e = s.energies;
    const double balance = e.total() + s.dissipated - s.actuator_work;
    t.add_row({s.t, e.kinetic, e.gravitational, e.internal, e.leg, e.contact, s.dissipated,
               s.actuator_work, balance});
  }
  return t;
}

Table robot_feet_table(const robot::RobotRunResult& r) {
  const size_t legs = r.samples.empty() ? 0 : r.samples.front().actuator_force.size();
  const size_t feet = r.samples.empty() ? 0 : r.samples.front().normal_force.size();
  Table t;
  t.columns = {"t"};
  for (size_t i = 0; i < legs; ++i) t.columns.push_back("F_act" + std::to_string(i));
  for (size_t i = 0; i < feet; ++i) t.columns.push_back("N" + std::to_string(i));
  for (size_t i = 0; i < feet; ++i) t.columns.push_back("z_foot" + std::to_string(i));
  t.data.reserve(r.samples.size() * t.columns.size());
  for (const auto& s : r.samples) {
    t.data.push_back(s.t);
    t.data.insert(t.data.end(), s.actuator_force.begin(), s.actuator_force.end());
    t.data.insert(t.data.end(), s.normal_force.begin(), s.normal_force.end());
    t.data.insert(t.data.end(), s.foot_z.begin(), s.foot_z.end());
  }
  return t;
}

std::string robot_energy_csv(const robot::RobotRunResult& r) {
  return table_csv(robot_energy_table(r));
}

std::string robot_feet_csv(const robot::RobotRunResult& r) {
  return table_csv(robot_feet_table(r));
}

void write_robot_outputs(const std::string& dir, const scene::Scene& scene,
                         const robot::RobotRunResult& r, const reduced::RunMetrics& metrics,
                         const robot::FidelityDiscrepancy* pulse, FigureBatch& figures) {
  write_run_files(dir, scene, r.run, robot_summary_json(scene, r, metrics, pulse), figures);
  write_file_atomic(dir + "/energy.csv", robot_energy_csv(r));
  write_file_atomic(dir + "/feet.csv", robot_feet_csv(r));
  // A MuJoCo run's robot as MuJoCo's own model, for its viewer (keyframe "initial": the start).
  if (!r.mjcf.empty()) write_file_atomic(dir + "/robot.xml", r.mjcf);
  const size_t legs = r.samples.empty() ? 0 : r.samples.front().actuator_force.size();
  const bool feet = !r.samples.empty() && !r.samples.front().normal_force.empty();
  figures.add(dir, "hop_forces", figure_hop(legs, feet));
  figures.add(dir, "energy", figure_energy());
  figures.add(dir, "path3d", figure_path());
}

}  // namespace pronk::io
