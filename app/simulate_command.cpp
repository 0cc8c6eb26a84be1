#include "app/simulate_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "sim/io/json_reader.hpp"
#include "sim/io/run_output.hpp"
#include "sim/io/scene_loader.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/reduced/simulator.hpp"

namespace pronk::app {

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate one robot scene and write trajectory.csv, strides.csv, summary.json,\n"
      "scene.resolved.json and SVG figures (with their gnuplot scripts) to the output directory.");
  cmd->add_option("scene", args.scene_path, "Scene file (JSON)")->required();
  cmd->add_option("--model", args.model, "Model: impulse or pulse (default: the scene's)")
      ->check(CLI::IsMember({"impulse", "pulse"}));
  cmd->add_option("--set", args.overrides,
                  "Override a scene value: --set /json/pointer=value (repeatable)")
      ->type_name("/PTR=VALUE");
  cmd->add_option("--out", args.out_dir, "Output directory (default: out/<scene name>)");
  cmd->add_flag("--quiet,-q", args.quiet, "Print nothing on success");
  return cmd;
}

int run_simulate(const SimulateArgs& args) {
  nlohmann::json doc = io::read_json_file(args.scene_path);
  for (const auto& o : args.overrides) io::apply_override(doc, o);
  if (!args.model.empty()) io::apply_override(doc, "/model=\"" + args.model + "\"");
  const scene::Scene scene = io::parse_scene(doc, args.scene_path);
  const reduced::RunResult run = reduced::simulate(scene);
  const reduced::RunMetrics metrics = reduced::compute_metrics(scene, run);
  const std::string dir = args.out_dir.empty() ? "out/" + scene.name : args.out_dir;
  io::write_run_outputs(dir, scene, run, metrics);
  if (!args.quiet) {
    const auto& c = run.cost.solver;
    std::printf("%s (%s model): %s, %s\n", scene.name.c_str(),
                std::string(scene::to_string(scene.model)).c_str(),
                std::string(reduced::to_string(run.status)).c_str(), run.reason.c_str());
    std::printf("  strides %ld, final error x %.4f m, y %.4f m, roll %.3f deg, pitch %.3f deg\n",
                metrics.strides, metrics.final_x_error, metrics.final_y_error,
                metrics.final_roll * 180 / M_PI, metrics.final_pitch * 180 / M_PI);
    std::printf("  apex error after first stride: max %.3g m; duty cycle mean %.3f max %.3f\n",
                metrics.max_apex_error, metrics.mean_duty, metrics.max_duty);
    std::printf("  cost: %ld steps (%ld rejected), %ld RHS evaluations, %ld events, %.3f ms\n",
                c.steps_accepted, c.steps_rejected, c.rhs_evaluations, c.events,
                run.cost.wall_time * 1e3);
    std::printf("  outputs in %s/\n", dir.c_str());
  }
  return run.status == reduced::RunStatus::kCompleted ? 0 : 1;
}

}  // namespace pronk::app
