#include "io/write/mechanism_output.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "io/write/atomic_file.hpp"
#include "io/write/figure_batch.hpp"
#include "io/write/method_choice_output.hpp"
#include "io/write/run_output.hpp"
#include "sim/math/rotation.hpp"
#include "sim/pseudorigid/system.hpp"

namespace pronk::io {

namespace pr = pronk::pseudorigid;
using nlohmann::json;

namespace {

/// Appends ",x" (or "x" first in a row) as %.10g (std::to_chars with a precision prints as
/// printf does); a non-finite value is a bug, never output.
void put(std::string& row, double x, bool first = false) {
  if (!std::isfinite(x)) throw std::logic_error("mechanism output: non-finite value in a CSV row");
  char buf[40];
  char* at = buf;
  if (!first) *at++ = ',';
  const std::to_chars_result r =
      std::to_chars(at, buf + sizeof buf, x, std::chars_format::general, 10);
  row.append(buf, r.ptr);
}

std::vector<std::pair<std::string, pr::NodeRef>> output_nodes(const pr::Mechanism& m) {
  std::vector<std::pair<std::string, pr::NodeRef>> out;
  for (size_t i = 0; i < m.masses.size(); ++i) {
    out.emplace_back(m.masses[i].name, pr::NodeRef{pr::NodeRef::Kind::kMass, static_cast<int>(i)});
  }
  for (size_t i = 0; i < m.ghost_points.size(); ++i) {
    out.emplace_back(m.ghost_points[i].name,
                     pr::NodeRef{pr::NodeRef::Kind::kGhost, static_cast<int>(i)});
  }
  return out;
}

/// Column names must not break the CSV: commas and quotes become '_'.
std::string column(std::string name) {
  for (char& c : name) {
    if (c == ',' || c == '"' || c == '\'' || c == '\n') c = '_';
  }
  return name;
}

const char* kSvgHeader =
    "set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'\n"
    "set datafile separator ','\nset key autotitle columnhead\nset grid\n";

std::string gp_title(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\'' || c == '\n') continue;
    if (c == '_' || c == '^' || c == '@' || c == '&' || c == '{' || c == '}') out += '\\';
    out += c;
  }
  return out;
}

std::string figure_energy(const std::string& title) {
  return std::string(kSvgHeader) + "set output 'energy.svg'\nset multiplot layout 2,1 title '" +
         gp_title(title) +
         ": energies'\nset ylabel 'energy [J]'\n"
         "plot 'energy.csv' u 1:2 w l t 'kinetic', '' u 1:3 w l t 'gravitational', "
         "'' u 1:5 w l t 'internal springs', '' u 1:6 w l t 'leg springs', "
         "'' u 1:7 w l t 'other springs', '' u 1:8 w l t 'contact', "
         "'' u 1:9 w l t 'dissipated', '' u 1:10 w l t 'actuator work'\n"
         "set xlabel 't [s]'\nset ylabel 'balance - initial [J]'\n"
         "plot 'energy.csv' u 1:($12-b0) w l t 'energy balance drift'\nunset multiplot\n";
}

std::string figure_motion(const pr::Mechanism& m, const std::string& title) {
  std::string s = std::string(kSvgHeader) + "set output 'motion.svg'\n";
  if (m.bodies.empty()) {
    // Free masses only: their heights and horizontal positions.
    s += "set multiplot layout 2,1 title '" + gp_title(title) +
         ": node motion'\nset ylabel 'x [m]'\nplot ";
    const size_t n = std::min<size_t>(m.masses.size(), 8);
    for (size_t i = 0; i < n; ++i) {
      s += (i ? ", " : "") + std::string("'nodes.csv' u 1:") + std::to_string(2 + 3 * i) + " w l";
    }
    s += "\nset xlabel 't [s]'\nset ylabel 'z [m]'\nplot ";
    for (size_t i = 0; i < n; ++i) {
      s += (i ? ", " : "") + std::string("'nodes.csv' u 1:") + std::to_string(4 + 3 * i) + " w l";
    }
    return s + "\nunset multiplot\n";
  }
  s += "set multiplot layout 3,1 title '" + gp_title(title) + ": body motion'\n";
  const size_t nb = std::min<size_t>(m.bodies.size(), 4);
  auto panel = [&](const char* ylabel, int offset) {
    s += std::string("set ylabel '") + ylabel + "'\nplot ";
    for (size_t b = 0; b < nb; ++b) {
      for (int k = 0; k < 3; ++k) {
        s += (b || k ? ", " : "") + std::string("'bodies.csv' u 1:") +
             std::to_string(2 + 9 * b + offset + k) + " w l";
      }
    }
    s += "\n";
  };
  panel("CoM [m]", 0);
  panel("Euler angles [rad]", 3);
  s += "set xlabel 't [s]'\n";
  panel("angular velocity [rad/s]", 6);
  return s + "unset multiplot\n";
}

}  // namespace

std::string mechanism_nodes_csv(const pr::Mechanism& m, const pr::RunSummary& run) {
  const auto nodes = output_nodes(m);
  std::string out = "t";
  for (const auto& [name, n] : nodes) {
    (void)n;
    const std::string c = column(name);
    out += "," + c + "_x," + c + "_y," + c + "_z";
  }
  out += "\n";
  pr::MechanismSystem sys(m);
  for (size_t i = 0; i < run.t.size(); ++i) {
    std::string row;
    put(row, run.t[i], true);
    for (const auto& [name, n] : nodes) {
      (void)name;
      const Eigen::Vector3d x = sys.node_position(n, run.y[i]);
      for (int k = 0; k < 3; ++k) put(row, x[k]);
    }
    out += row;
    out += '\n';
  }
  return out;
}

std::string mechanism_bodies_csv(const pr::Mechanism& m, const pr::RunSummary& run) {
  const bool s313 = m.simulation.euler_313;
  const char* a[3] = {s313 ? "psi" : "roll", s313 ? "theta" : "pitch", s313 ? "phi" : "yaw"};
  std::string out = "t";
  for (const pr::Body& b : m.bodies) {
    const std::string c = column(b.name);
    out += "," + c + "_x," + c + "_y," + c + "_z";
    for (const char* name : a) out += "," + c + "_" + name;
    out += "," + c + "_wx," + c + "_wy," + c + "_wz";
  }
  out += "\n";
  pr::MechanismSystem sys(m);
  const math::EulerSet set = s313 ? math::EulerSet::k313 : math::EulerSet::k123;
  for (size_t i = 0; i < run.t.size(); ++i) {
    std::string row;
    put(row, run.t[i], true);
    const std::vector<pr::BodyFrame> frames = sys.frames(run.y[i]);
    for (size_t b = 0; b < m.bodies.size(); ++b) {
      const Eigen::Vector3d e = math::matrix_to_euler(frames[b].rotation, set);
      const Eigen::Vector3d w = sys.body_omega(static_cast<int>(b), run.y[i]);
      for (int k = 0; k < 3; ++k) put(row, frames[b].com[k]);
      for (int k = 0; k < 3; ++k) put(row, e[k]);
      for (int k = 0; k < 3; ++k) put(row, w[k]);
    }
    out += row;
    out += '\n';
  }
  return out;
}

std::string mechanism_energy_csv(const pr::RunSummary& run) {
  std::string out =
      "t,kinetic,gravitational,applied,internal,leg,other,contact,dissipated,actuator_work,"
      "total,balance\n";
  for (size_t i = 0; i < run.t.size(); ++i) {
    const pr::Energies& e = run.energies[i];
    std::string row;
    put(row, run.t[i], true);
    for (double x : {e.kinetic, e.gravitational, e.applied, e.internal, e.leg, e.other, e.contact,
                     run.dissipated[i], run.actuator_work[i], e.total(),
                     e.total() + run.dissipated[i] - run.actuator_work[i]}) {
      put(row, x);
    }
    out += row;
    out += '\n';
  }
  return out;
}

json mechanism_summary_json(const LoadedMechanism& scene, const pr::RunSummary& run) {
  const pr::Mechanism& m = scene.mechanism;
  json j;
  j["name"] = m.name;
  j["kind"] = "mechanism";
  j["status"] = std::string(pr::to_string(run.status));
  j["reason"] = run.reason;
  j["t_reached"] = run.t_reached;
  j["method"] = std::string(ode::to_string(m.simulation.solver.method));
  j["error_norm"] = m.simulation.error_norm == pr::ErrorNorm::kBody ? "body" : "state";
  j["states"] = m.dimension();
  const auto& c = run.counters;
  j["cost"] = {
      {"steps_accepted", c.steps_accepted},       {"steps_rejected", c.steps_rejected},
      {"rhs_evaluations", c.rhs_evaluations},     {"jacobian_evaluations", c.jacobian_evaluations},
      {"lu_factorizations", c.lu_factorizations}, {"wall_time_s", run.wall_time}};
  json mon = {{"energy_scale_J", run.energy_scale},
              {"energy_balance_drift_J", run.energy_drift},
              {"energy_balance_drift_relative", run.energy_drift / run.energy_scale},
              {"max_internal_strain", run.max_strain},
              {"max_penetration_m", run.max_penetration},
              {"zero_length_triggers", run.zero_length_triggers}};
  json sf = json::object();
  for (size_t i = 0; i < m.surfaces.size() && i < run.max_surface_force.size(); ++i) {
    sf[m.surfaces[i].name] = run.max_surface_force[i];
  }
  mon["max_surface_force_N"] = sf;
  if (run.jacobian_check_error >= 0.0) mon["jacobian_check_error"] = run.jacobian_check_error;
  j["monitors"] = mon;
  json warnings = json::object();
  for (const auto& [id, text] : run.warnings) warnings[id] = text;
  j["warnings"] = warnings;
  json st = {{"internal_auto", scene.internal_auto}, {"contact_auto", scene.contact_auto}};
  if (scene.internal_auto) {
    st["internal_min_N_per_m"] = scene.stiffness.internal_min;
    st["internal_max_N_per_m"] = scene.stiffness.internal_max;
  }
  if (scene.contact_auto) st["contact_N_per_m"] = scene.stiffness.contact;
  if (scene.internal_auto || scene.contact_auto) st["note"] = scene.stiffness.note;
  j["stiffness"] = st;
  if (scene.method_auto) {
    add_method_choice(scene.method_choice, run.energy_drift / run.energy_scale, &j);
  }
  if (!run.t.empty()) {
    const pr::Energies& e = run.energies.back();
    j["final"] = {{"t", run.t.back()},
                  {"energy_total_J", e.total()},
                  {"dissipated_J", run.dissipated.back()},
                  {"actuator_work_J", run.actuator_work.back()}};
  }
  return j;
}

bool write_mechanism_outputs(const std::string& dir, const LoadedMechanism& scene,
                             const pr::RunSummary& run) {
  const pr::Mechanism& m = scene.mechanism;
  make_directories(dir);
  write_file_atomic(dir + "/nodes.csv", mechanism_nodes_csv(m, run));
  write_file_atomic(dir + "/bodies.csv", mechanism_bodies_csv(m, run));
  write_file_atomic(dir + "/energy.csv", mechanism_energy_csv(run));
  write_file_atomic(dir + "/summary.json", dump_checked(mechanism_summary_json(scene, run)));
  write_file_atomic(dir + "/scene.resolved.json", dump_checked(scene.resolved));
  if (run.t.empty()) return false;
  char b0[64];
  const pr::Energies& e0 = run.energies.front();
  std::snprintf(b0, sizeof b0, "b0 = %.17g\n",
                e0.total() + run.dissipated[0] - run.actuator_work[0]);
  FigureBatch figures;
  figures.add(dir, "energy", std::string(b0) + figure_energy(m.name));
  figures.add(dir, "motion", figure_motion(m, m.name));
  return figures.finish();
}

}  // namespace pronk::io
