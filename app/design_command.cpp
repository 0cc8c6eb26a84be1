#include "app/design_command.hpp"

#include <cstdio>
#include <filesystem>

#include "app/optimize_command.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/atomic_file.hpp"
#include "optimize/design/design_study.hpp"

namespace pronk::app {

namespace fs = std::filesystem;

CLI::App* add_design_command(CLI::App& app, DesignArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "design",
      "From a robot to a running design: derive a staged study from the robot's scene (only its\n"
      "body, legs and target gait are needed), write it to DIR/study.json, run it (the pulse\n"
      "model, then the full model, every trial disturbed and the robot perturbed) and validate\n"
      "the design on held-out trials. `pronk optimize DIR/study.json --out DIR` reruns it.");
  auto& o = args.options;
  cmd->add_option("scene", args.scene_path, "The robot's scene (JSON)")->required();
  cmd->add_option("--out", args.out_dir, "Output directory")->required();
  cmd->add_option("--set", args.overrides,
                  "Override a scene value first: --set /json/pointer=value (repeatable), e.g. "
                  "--set /body/mass=2.2; DIR/scene.json is the scene with them")
      ->type_name("/PTR=VALUE");
  cmd->add_option("--model", o.final_model, "Final model: pseudo_rigid (default) or pulse")
      ->check(CLI::IsMember({"pulse", "pseudo_rigid"}));
  cmd->add_option("--budget", o.full_evaluations, "Evaluations of the final (full-model) stage")
      ->check(CLI::Range(1L, 1000000L));
  cmd->add_option("--pulse-budget", o.pulse_evaluations, "Evaluations of the pulse stage")
      ->check(CLI::Range(1L, 1000000L));
  cmd->add_option("--optimizer", o.full_optimizer,
                  "Full-model stage: bobyqa (NLopt, local) or cmaes (pagmo, global)")
      ->check(CLI::IsMember({"bobyqa", "cmaes"}));
  cmd->add_option("--population", o.population, "cmaes population")->check(CLI::Range(5L, 10000L));
  cmd->add_option("--duty", args.duty, "Duty-cycle range LO,HI (stance / stride; default 0.14,0.26), started in its middle")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--tilt", o.tilt_deg, "Largest start tilt of a trial [deg]");
  cmd->add_option("--offset", o.lateral_offset, "Largest start lateral offset [m]");
  cmd->add_option("--kick", o.velocity_kick, "Largest start velocity kick [m/s]");
  cmd->add_option("--perturb", args.perturb,
                  "Robot perturbations MASS,INERTIA,STIFFNESS, relative half-widths "
                  "(default 0.15,0.2,0.15)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--friction", args.friction, "Foot friction range LO,HI (default 0.6,1.2)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_flag("--tune-nominal", o.tune_nominal,
                "Tune on the nominal robot only (the validation still perturbs it)");
  cmd->add_option("--trials", o.scenarios, "Tuning trials per evaluation")
      ->check(CLI::Range(1L, 100000L));
  cmd->add_option("--validation", o.validation, "Held-out validation trials")
      ->check(CLI::Range(1L, 100000L));
  cmd->add_option("--duration", o.duration, "Simulated seconds per trial");
  cmd->add_option("--seed", o.seed, "Seed of every draw and optimizer")->check(CLI::Range(0L, 1L << 40));
  cmd->add_option("--threads", args.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("--resume", args.resume, "Continue the design in DIR");
  cmd->add_flag("--study-only", args.study_only, "Write DIR/study.json and stop");
  cmd->add_flag("--quiet,-q", args.quiet, "No progress line, no summary");
  return cmd;
}

namespace {

std::string pretty(const nlohmann::json& j) { return j.dump(2) + "\n"; }

// DIR/study.json: new, or (with --resume) the one this command wrote with the same options.
void write_or_check_study(const DesignArgs& args, const std::string& path,
                          const nlohmann::json& study) {
  if (fs::exists(path)) {
    if (!args.resume) {
      throw io::InputError("--out", "",
                           "a directory without a design study (or --resume to continue it)",
                           "\"" + path + "\"");
    }
    if (io::read_json_file(path) != study) {
      throw io::InputError(path, "",
                           "the study these options derive (--resume continues only the same "
                           "design; an edited study reruns with `pronk optimize`)",
                           "a different study");
    }
    return;
  }
  io::write_file_atomic(path, pretty(study));
}

}  // namespace

int run_design(DesignArgs args) {
  auto& o = args.options;
  if (args.duty.size() == 2) {
    o.duty_lo = args.duty[0], o.duty_hi = args.duty[1];
    o.duty = 0.5 * (o.duty_lo + o.duty_hi);
  }
  if (args.perturb.size() == 3)
    o.mass = args.perturb[0], o.inertia = args.perturb[1], o.leg_stiffness = args.perturb[2];
  if (args.friction.size() == 2) o.friction_lo = args.friction[0], o.friction_hi = args.friction[1];
  std::string err;
  if (!o.validate(&err)) {
    const std::string field = err.substr(0, err.find(':'));
    throw io::InputError("--" + field, "", "a valid design option", err.substr(field.size() + 2));
  }
  nlohmann::json scene = io::read_json_file(args.scene_path);
  for (const auto& assignment : args.overrides) io::apply_override(scene, assignment);
  const nlohmann::json study =
      optimize::derive_design_study(scene, args.scene_path, "scene.json", o);
  io::make_directories(args.out_dir);
  const std::string scene_copy = (fs::path(args.out_dir) / "scene.json").string();
  const std::string study_path = (fs::path(args.out_dir) / "study.json").string();
  write_or_check_study(args, study_path, study);
  if (!fs::exists(scene_copy) || io::read_json_file(scene_copy) != scene)
    io::write_file_atomic(scene_copy, pretty(scene));
  if (!args.quiet) std::printf("%s: the derived study\n", study_path.c_str());
  if (args.study_only) return 0;
  OptimizeArgs run;
  run.study_path = study_path;
  run.threads = args.threads;
  run.resume = args.resume;
  run.out_dir = args.out_dir;
  run.quiet = args.quiet;
  return run_optimize(run);
}

}  // namespace pronk::app
