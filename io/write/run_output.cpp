#include "io/write/run_output.hpp"

#include <cmath>
#include <stdexcept>

#include "io/build_info.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/figure_batch.hpp"

namespace pronk::io {

using json = nlohmann::json;

namespace {
constexpr double kRadToDeg = 180.0 / M_PI;

void check_finite(const json& j, const std::string& ptr) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    throw std::logic_error("non-finite number in output at " + ptr);
  }
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) check_finite(*it, ptr + "/" + it.key());
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) check_finite(j[i], ptr + "/" + std::to_string(i));
  }
}

}  // namespace

std::string dump_checked(const json& j) {
  check_finite(j, "");
  return j.dump(2) + "\n";
}

json run_summary_json(const scene::Scene& scene, const reduced::RunResult& run,
                      const reduced::RunMetrics& m) {
  json warnings = json::object();
  for (const auto& [k, v] : run.warnings) warnings[k] = v;
  const auto& c = run.cost.solver;
  return {{"scene", scene.name},
          {"model", std::string(scene::to_string(scene.model))},
          {"status", std::string(reduced::to_string(run.status))},
          {"reason", run.reason},
          {"t_end", run.t_end},
          {"metrics",
           {{"strides", m.strides},
            {"final_x_error_m", m.final_x_error},
            {"final_y_error_m", m.final_y_error},
            {"final_roll_deg", m.final_roll * kRadToDeg},
            {"final_pitch_deg", m.final_pitch * kRadToDeg},
            {"max_apex_error_m", m.max_apex_error},
            {"last_apex_error_m", m.last_apex_error},
            {"mean_duty_cycle", m.mean_duty},
            {"max_duty_cycle", m.max_duty},
            {"max_tilt_deg", m.max_tilt * kRadToDeg},
            {"peak_leg_force_N", m.peak_leg_force},
            {"mean_impulse_per_stride_Ns", m.mean_impulse_per_stride},
            {"settle_strides", m.settle_strides}}},
          {"cost",
           {{"steps_accepted", c.steps_accepted},
            {"steps_rejected", c.steps_rejected},
            {"rhs_evaluations", c.rhs_evaluations},
            {"events", c.events},
            {"touchdowns", run.cost.touchdowns},
            {"wall_time_s", run.cost.wall_time}}},
          {"monitors",
           {{"max_event_residual_m", run.monitors.max_event_residual},
            {"max_flight_energy_drift", run.monitors.max_flight_energy_drift},
            {"max_quaternion_norm_error", run.monitors.max_quaternion_norm_error}}},
          {"warnings", warnings},
          {"unused_by_this_model", unused_settings(scene)},
          {"solver",
           {{"method", std::string(ode::to_string(scene.simulation.solver.method))},
            {"rtol", scene.simulation.solver.rtol},
            {"atol", scene.simulation.solver.atol}}},
          {"version", pronk::version()},
          {"commit", pronk::git_commit()}};
}

Table trajectory_table(const reduced::RunResult& run) {
  Table t;
  t.columns = {"t",  "x",  "y",  "z",   "vx",  "vy",     "vz", "roll_deg", "pitch_deg", "yaw_deg",
               "wx", "wy", "wz", "x_d", "y_d", "stance", "Fx", "Fy",       "Fz"};
  t.data.reserve(run.trajectory.size() * t.columns.size());
  for (const auto& s : run.trajectory) {
    const Eigen::Vector3d a = s.euler123 * kRadToDeg;
    t.add_row({s.t, s.position.x(), s.position.y(), s.position.z(), s.velocity.x(), s.velocity.y(),
               s.velocity.z(), a.x(), a.y(), a.z(), s.omega.x(), s.omega.y(), s.omega.z(),
               s.setpoint.x(), s.setpoint.y(), s.stance ? 1.0 : 0.0, s.leg_force_world.x(),
               s.leg_force_world.y(), s.leg_force_world.z()});
  }
  return t;
}

Table strides_table(const reduced::RunResult& run) {
  Table t;
  t.columns = {"stride",
               "t_touchdown",
               "x",
               "y",
               "z",
               "vx",
               "vy",
               "vz",
               "roll_deg",
               "pitch_deg",
               "yaw_deg",
               "x_d",
               "y_d",
               "apex_height",
               "stance_duration",
               "stride_time",
               "duty_cycle",
               "Px_req",
               "Py_req",
               "Pz_req",
               "Hx_req",
               "Hy_req",
               "Hz_req",
               "Px_del",
               "Py_del",
               "Pz_del",
               "Hx_del",
               "Hy_del",
               "Hz_del",
               "gravity_compensation",
               "peak_leg_force",
               "active_legs",
               "allocation_ok"};
  t.data.reserve(run.strides.size() * t.columns.size());
  for (const auto& s : run.strides) {
    const Eigen::Vector3d a = s.euler123 * kRadToDeg;
    t.add_row({static_cast<double>(s.index),
               s.t_touchdown,
               s.position.x(),
               s.position.y(),
               s.position.z(),
               s.velocity.x(),
               s.velocity.y(),
               s.velocity.z(),
               a.x(),
               a.y(),
               a.z(),
               s.setpoint.x(),
               s.setpoint.y(),
               s.has_apex ? s.apex_height : 0.0,
               s.stance_duration,
               s.stride_time,
               s.duty_cycle,
               s.P_requested.x(),
               s.P_requested.y(),
               s.P_requested.z(),
               s.H_requested.x(),
               s.H_requested.y(),
               s.H_requested.z(),
               s.P_delivered.x(),
               s.P_delivered.y(),
               s.P_delivered.z(),
               s.H_delivered.x(),
               s.H_delivered.y(),
               s.H_delivered.z(),
               s.gravity_compensation,
               s.peak_leg_force,
               static_cast<double>(s.active_legs),
               s.allocation == control::AllocationStatus::kOk ? 1.0 : 0.0});
  }
  return t;
}

std::string trajectory_csv(const reduced::RunResult& run) {
  return table_csv(trajectory_table(run));
}

std::string strides_csv(const reduced::RunResult& run) { return table_csv(strides_table(run)); }

namespace {
const char* kSvgHeader =
    "set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'\n"
    "set datafile separator ','\nset key autotitle columnhead\nset grid\n";

}  // namespace

std::string path3d_z_axis() {
  // The z axis of a 3-D CoM path is short on the page: from the ground up, at most four
  // round ticks (1, 2 or 5 times a power of ten), the label beside the axis, the floor at z = 0.
  return "stats 'trajectory.csv' u 4 nooutput name 'PZ'\n"
         "pz_top = PZ_max > 0 ? PZ_max : 1\n"
         "pz_step = 10**floor(log10(pz_top / 3.0)); pz_r = pz_top / pz_step\n"
         "pz_step = pz_step * (pz_r <= 3 ? 1 : pz_r <= 6 ? 2 : pz_r <= 15 ? 5 : 10)\n"
         "set zrange [0:*]; set ztics 0, pz_step; set xyplane at 0\n"
         "set zlabel 'z [m]' rotate parallel\nset view 60,30,1,1.3\n";
}

namespace {

std::string figure_motion(const std::string& title) {
  return std::string(kSvgHeader) + "set output 'motion.svg'\nset multiplot layout 2,2 title '" +
         title +
         "' noenhanced\n"
         "set title 'Body position'; set xlabel 'time [s]'; set ylabel 'position [m]'\n"
         "plot 'trajectory.csv' u 1:2 w l t 'x', '' u 1:3 w l t 'y', '' u 1:4 w l t 'z', "
         "'' u 1:14 w l dt 2 t 'x_d'\n"
         "set title 'Body horizontal velocity'; set ylabel 'velocity [m/s]'\n"
         "plot 'trajectory.csv' u 1:5 w l t 'v_x', '' u 1:6 w l t 'v_y'\n"
         "set title 'Body attitude (Euler 1-2-3)'; set ylabel 'angle [deg]'\n"
         "plot 'trajectory.csv' u 1:8 w l t 'roll', '' u 1:9 w l t 'pitch', '' u 1:10 w l t "
         "'yaw'\n"
         "set title 'Trajectory of the CoM'; set xlabel 'x [m]'; set ylabel 'y [m]'\n" +
         path3d_z_axis() +
         "splot 'trajectory.csv' u 2:3:4 w l t 'CoM'\n"
         "unset multiplot\n";
}

std::string figure_strides() {
  return std::string(kSvgHeader) +
         "set output 'strides.svg'\nset multiplot layout 2,1\n"
         "set title 'Apex height per stride'; set xlabel 'stride'; set ylabel 'apex height [m]'\n"
         "plot 'strides.csv' u 1:($14>0?$14:1/0) w lp t 'apex'\n"
         "set title 'Duty cycle per stride'; set ylabel 'stance / stride time'\n"
         "plot 'strides.csv' u 1:($16>0?$17:1/0) w lp t 'duty cycle'\n"
         "unset multiplot\n";
}

std::string figure_leg_force() {
  return std::string(kSvgHeader) +
         "set output 'leg_force.svg'\n"
         "set title 'Net leg force (world)'; set xlabel 'time [s]'; set ylabel 'force [N]'\n"
         "plot 'trajectory.csv' u 1:17 w l t 'F_x', '' u 1:18 w l t 'F_y', '' u 1:19 w l t "
         "'F_z'\n";
}
}  // namespace

void write_run_outputs(const std::string& dir, const scene::Scene& scene,
                       const reduced::RunResult& run, const reduced::RunMetrics& metrics,
                       FigureBatch& figures) {
  write_run_files(dir, scene, run, run_summary_json(scene, run, metrics), figures);
}

void write_run_files(const std::string& dir, const scene::Scene& scene,
                     const reduced::RunResult& run, const nlohmann::json& summary,
                     FigureBatch& figures) {
  make_directories(dir);
  write_file_atomic(dir + "/scene.resolved.json", dump_checked(scene_to_json(scene)));
  write_file_atomic(dir + "/trajectory.csv", trajectory_csv(run));
  write_file_atomic(dir + "/strides.csv", strides_csv(run));
  write_file_atomic(dir + "/summary.json", dump_checked(summary));
  const std::string title = scene.name + " (" + std::string(scene::to_string(scene.model)) + ")";
  figures.add(dir, "motion", figure_motion(title));
  if (run.strides.size() >= 2) {
    figures.add(dir, "strides", figure_strides());
  } else {
    write_file_atomic(dir + "/strides.gp", figure_strides());  // nothing to plot yet
  }
  if (scene.model == scene::ModelKind::kPulse) figures.add(dir, "leg_force", figure_leg_force());
}

}  // namespace pronk::io
