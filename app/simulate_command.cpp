#include "app/simulate_command.hpp"
#include "app/view_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "io/load/json_reader.hpp"
#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/page/page_data.hpp"
#include "io/write/mechanism_output.hpp"
#include "io/write/simulation_output.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/reduced/setpoint_check.hpp"
#include "sim/robot/accuracy_check.hpp"
#include "sim/run/count_text.hpp"
#include "sim/scene/scene.hpp"
#include "sim/simulate.hpp"

namespace pronk::app {

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate one robot scene and write trajectory.csv, strides.csv, summary.json,\n"
      "scene.resolved.json, SVG figures (with their gnuplot scripts) and view.html (3-D playback)\n"
      "to the output directory. A scene with \"kind\": \"mechanism\" is a pseudo-rigid mechanism:\n"
      "nodes.csv, bodies.csv, energy.csv, summary.json, scene.resolved.json, energy.svg,\n"
      "motion.svg, view.html.");
  cmd->add_option("scene", args.scene_path, "Scene file (JSON)")->required();
  cmd->add_option("--model", args.model,
                  "Model: impulse, pulse, pseudo_rigid or mujoco (default: the scene's)")
      ->check(CLI::IsMember(scene::model_names()));
  cmd->add_option("--set", args.overrides,
                  "Override a scene value: --set /json/pointer=value (repeatable)")
      ->type_name("/PTR=VALUE");
  cmd->add_option("--out", args.out_dir, "Output directory (default: out/<scene name>)");
  cmd->add_flag("--quiet,-q", args.quiet,
                "Print nothing on success (a run that does not complete still says so on stderr)");
  return cmd;
}

namespace {

/// A generic pseudo-rigid mechanism scene (top-level "kind": "mechanism").
int run_mechanism(const SimulateArgs& args, const nlohmann::json& doc) {
  io::LoadedMechanism scene = io::parse_mechanism(doc, args.scene_path);
  const pseudorigid::RunSummary run = io::simulate_loaded(&scene);
  const std::string dir = args.out_dir.empty() ? "out/" + scene.mechanism.name : args.out_dir;
  io::write_mechanism_outputs(dir, scene, run);
  const std::string page = io::page::write_directory_page(dir);
  if (!args.quiet) {
    const auto& c = run.counters;
    std::printf("%s (mechanism, %s): %s, %s\n", scene.mechanism.name.c_str(),
                std::string(ode::to_string(scene.mechanism.simulation.solver.method)).c_str(),
                std::string(pseudorigid::to_string(run.status)).c_str(), run.reason.c_str());
    std::printf(
        "  energy balance drift %.3g J (%.3g of scale), max strain %.3g, max penetration "
        "%.3g m, zero-length triggers %ld\n",
        run.energy_drift, run.energy_drift / run.energy_scale, run.max_strain, run.max_penetration,
        run.zero_length_triggers);
    std::printf("  cost: %ld steps (%ld rejected), %ld RHS, %ld Jacobians, %ld LU, %.3f ms\n",
                c.steps_accepted, c.steps_rejected, c.rhs_evaluations, c.jacobian_evaluations,
                c.lu_factorizations, run.wall_time * 1e3);
    for (const auto& [id, text] : run.warnings) {
      std::printf("  warning (%s): %s\n", id.c_str(), text.c_str());
    }
    if (run.jacobian_check_error >= 0.0) {
      std::printf("  Jacobian check: max relative difference %.3g\n", run.jacobian_check_error);
    }
    std::printf("  outputs in %s/\n", dir.c_str());
    print_page_line(page);
  } else if (run.status != pseudorigid::RunStatus::kCompleted) {
    std::fprintf(
        stderr, "pronk simulate: %s: %s, %s (outputs in %s/)\n", scene.mechanism.name.c_str(),
        std::string(pseudorigid::to_string(run.status)).c_str(), run.reason.c_str(), dir.c_str());
  }
  return run.status == pseudorigid::RunStatus::kCompleted ? 0 : 1;
}

// The setpoint check's warnings, with the distance: `completed` alone is not the whole story.
void print_setpoint_check(const reduced::SetpointCheck& c) {
  if (c.far) {
    std::printf("  warning: far from the setpoint: ended %.3g m from it (%.1f hop heights)\n",
                c.distance, c.hop_heights);
  }
  if (c.never_settled) {
    std::printf(
        "  warning: never settled (position within 1 cm, roll and pitch within 1 deg, apex "
        "within 5 mm from some stride to the end); ended %.3g m from the setpoint\n",
        c.distance);
  }
}

// One line per fact of a robot run, in any model.
void print_robot_run(const scene::Scene& scene, const RunResult& r,
                     const reduced::RunMetrics& metrics, const reduced::SetpointCheck& setpoint,
                     const robot::AccuracyCheck& accuracy, const std::string& dir,
                     const std::string& page) {
  const auto& c = r.run.cost.solver;
  std::printf("%s (%s model): %s, %s\n", scene.name.c_str(),
              std::string(scene::to_string(scene.model)).c_str(),
              std::string(reduced::to_string(r.run.status)).c_str(), r.run.reason.c_str());
  std::printf("  strides %ld, final error x %.4f m, y %.4f m, roll %.3f deg, pitch %.3f deg\n",
              metrics.strides, metrics.final_x_error, metrics.final_y_error,
              metrics.final_roll * 180 / M_PI, metrics.final_pitch * 180 / M_PI);
  std::printf("  apex error after first stride: max %.3g m; duty cycle mean %.3f max %.3f\n",
              metrics.max_apex_error, metrics.mean_duty, metrics.max_duty);
  if (r.full_model()) {
    const auto& m = r.monitors;
    if (m.energy_measured) {
      std::printf(
          "  energy balance drift %.3g J (%.3g of scale), max strain %.3g, max penetration %.3g "
          "m, max slip %.3g m\n",
          m.energy_drift, m.drift_relative(), m.max_strain, m.max_penetration, m.max_slip);
    } else {
      std::printf(
          "  energy balance not monitored (MuJoCo's contact and dampers dissipate by its own "
          "laws), max penetration %.3g m, max slip %.3g m\n",
          m.max_penetration, m.max_slip);
    }
    std::printf("  cost: %ld steps (%ld rejected), %ld RHS, %ld Jacobians, %ld LU, %.3f ms\n",
                c.steps_accepted, c.steps_rejected, c.rhs_evaluations, c.jacobian_evaluations,
                c.lu_factorizations, r.run.cost.wall_time * 1e3);
  } else {
    std::printf("  cost: %s (%ld rejected), %s, %s, %.3f ms\n",
                run::count_text(c.steps_accepted, "step").c_str(), c.steps_rejected,
                run::count_text(c.rhs_evaluations, "RHS evaluation").c_str(),
                run::count_text(c.events, "event").c_str(), r.run.cost.wall_time * 1e3);
  }
  for (const auto& [id, count] : r.run.warnings) {
    // Printed below, with their numbers.
    if (id == "far_from_setpoint" || id == "never_settled" || id == "energy_beyond_accuracy") {
      continue;
    }
    std::printf("  warning: %s (%ld)\n", id.c_str(), count);
  }
  if (accuracy.beyond) {
    std::printf("  warning: %s\n", robot::accuracy_warning_text(accuracy).c_str());
  }
  print_setpoint_check(setpoint);
  std::printf("  outputs in %s/\n", dir.c_str());
  print_page_line(page);
}

}  // namespace

int run_simulate(const SimulateArgs& args) {
  nlohmann::json doc = io::read_json_file(args.scene_path);
  for (const auto& o : args.overrides) io::apply_override(doc, o);
  if (io::is_mechanism_document(doc)) {
    // --model chooses a fidelity of a robot scene; it lands on "/model", which the
    // strict mechanism reader rejects as an unknown key (exit 2).
    if (!args.model.empty()) io::apply_override(doc, "/model=\"" + args.model + "\"");
    return run_mechanism(args, doc);
  }
  if (!args.model.empty()) io::apply_override(doc, "/model=\"" + args.model + "\"");
  const scene::Scene scene = io::parse_scene(doc, args.scene_path);
  RunResult r;
  try {
    r = simulate(scene);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(args.scene_path, "/pseudo_rigid", "a robot the full model can build",
                         e.what());
  }
  const reduced::RunMetrics metrics = reduced::compute_metrics(scene, r.run);
  // The checks of a completed run: their warnings go to summary.json and the terminal.
  const reduced::SetpointCheck setpoint = reduced::check_setpoint(scene, r.run, metrics);
  reduced::add_setpoint_warnings(setpoint, &r.run.warnings);
  robot::AccuracyCheck accuracy;  // the reduced models keep no energy balance: no check
  if (r.full_model()) accuracy = robot::check_accuracy(scene, r);
  robot::add_accuracy_warning(accuracy, &r.run.warnings);
  const std::string dir = args.out_dir.empty() ? "out/" + scene.name : args.out_dir;
  const io::WrittenOutputs w = io::write_simulation_outputs(dir, scene, r, metrics);
  const bool ok = r.run.status == reduced::RunStatus::kCompleted;
  if (!args.quiet) {
    print_robot_run(scene, r, metrics, setpoint, accuracy, dir, w.page);
  } else if (!ok) {  // quiet keeps success silent, not a fall
    std::fprintf(stderr, "pronk simulate: %s: %s, %s (outputs in %s/)\n", scene.name.c_str(),
                 std::string(reduced::to_string(r.run.status)).c_str(), r.run.reason.c_str(),
                 dir.c_str());
  }
  return ok ? 0 : 1;
}

}  // namespace pronk::app
