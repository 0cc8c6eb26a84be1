#include "app/sensitivity_command.hpp"

#include <cmath>
#include <cstdio>

#include "app/mpi_command.hpp"
#include "app/optimize_command.hpp"
#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/design_reader.hpp"
#include "optimize/mpi/evaluation_farm.hpp"
#include "optimize/sensitivity/design_sensitivity.hpp"
#include "optimize/sensitivity/sensitivity_output.hpp"
#include "sim/run/count_text.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::app {

namespace {

namespace sens = optimize::sensitivity;

std::string default_out(const std::string& design_path) {
  const size_t slash = design_path.rfind('/');
  return (slash == std::string::npos ? std::string(".") : design_path.substr(0, slash)) +
         "/sensitivity";
}

sens::DesignSensitivityOptions options_of(const SensitivityArgs& a) {
  sens::DesignSensitivityOptions o;
  if (!a.model.empty()) o.model = a.model;
  o.validation = a.validation;
  o.plant = a.physical == "plant";
  o.local.step = a.local_step;
  o.sobol.samples = a.samples;
  o.sobol.bootstrap = a.bootstrap;
  o.sobol.seed = a.seed;
  o.default_range = a.default_range;
  if (!(a.default_range > 0.0 && a.default_range < 1.0)) {
    throw io::InputError("--default-range", "", "a relative range in (0, 1)",
                         std::to_string(a.default_range));
  }
  for (const auto& r : a.ranges) o.ranges.push_back(sens::parse_range_option(r));
  o.only = a.inputs;
  o.threads = thread_count(a.threads);
  o.progress = optimize::progress_style(a.quiet);
  return o;
}

}  // namespace

CLI::App* add_sensitivity_command(CLI::App& app, SensitivityArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "sensitivity",
      "Which numbers a tuned design (design.json) depends on: derivatives and elasticities of\n"
      "every objective and metric with respect to every tuned parameter and physical number\n"
      "(mass, inertia, and in the full model leg stiffness and friction), each input swung\n"
      "over its range (tornado chart), and Sobol indices over the ranges (docs/sensitivity.md).");
  cmd->add_option("design", args.design_path, "design.json written by pronk optimize")->required();
  cmd->add_option("--out", args.out, "Output directory (default: sensitivity/ beside the design)");
  cmd->add_option("--model", args.model, "Evaluate in this model instead of the study's")
      ->check(CLI::IsMember(scene::model_names()));
  cmd->add_flag("--validation", args.validation, "Evaluate on the study's validation set");
  cmd->add_option("--physical", args.physical,
                  "plant: a physical number changes the robot only, the controller keeps the "
                  "design's numbers (default); design: robot and controller alike")
      ->check(CLI::IsMember({"plant", "design"}));
  cmd->add_option("--local-step", args.local_step,
                  "Relative step h of the central differences (also h/2) (default 1e-2)");
  cmd->add_option("--samples", args.samples,
                  "Saltelli base samples N: N (k + 2) evaluations for k inputs; 0: no Sobol "
                  "indices (default 128)");
  cmd->add_option("--bootstrap", args.bootstrap, "Bootstrap resamples of the Sobol intervals");
  cmd->add_option("--default-range", args.default_range,
                  "Relative range of every input not given with --range (default 0.1)");
  cmd->add_option("--range", args.ranges,
                  "POINTER=REL: the relative range of an input (a tuned parameter's pointer or a "
                  "physical number of the resolved scene, added as an input); repeatable")
      ->type_name("POINTER=REL");
  cmd->add_option("--inputs", args.inputs,
                  "POINTER ...: only these inputs (a tuned parameter's pointer, or a physical "
                  "number of the resolved scene; default: every tuned parameter and the default "
                  "physical numbers)");
  cmd->add_option("--chart", args.chart, "The output the charts and summary show (default cost)");
  cmd->add_option("--seed", args.seed, "Seed of the Sobol sampling and bootstrap (default 1)");
  cmd->add_option("--threads", args.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_flag("-q,--quiet", args.quiet, "No progress lines");
  return cmd;
}

namespace {

// The run on rank 0 (or the only process): `farm` non-null under mpirun.
int run_loaded(const SensitivityArgs& args, const nlohmann::json& design, optimize::JobFarm* farm) {
  sens::DesignSensitivityOptions opt = options_of(args);
  opt.farm = farm;
  const sens::DesignSensitivity s = sens::design_sensitivity(design, args.design_path, opt);
  const size_t c = sens::chart_output(s, args.chart);
  const std::string out = args.out.empty() ? default_out(args.design_path) : args.out;
  sens::write_sensitivity(s, out, args.chart);
  if (!args.quiet) {
    std::printf(
        "sensitivity of %s (%s model, %s: %s): %s, %s, %s (%.1f s local, %.1f s Sobol)%s\n",
        s.study.c_str(), s.model.c_str(), s.set.c_str(),
        run::count_text(s.scenarios, "trial").c_str(),
        run::count_text(static_cast<long>(s.inputs.size()), "input").c_str(),
        run::count_text(static_cast<long>(s.outputs.size()), "output").c_str(),
        run::count_text(s.evaluations, "evaluation").c_str(), s.local_seconds, s.sobol_seconds,
        s.failed > 0 ? (", " + std::to_string(s.failed) + " made no valid scene").c_str() : "");
    std::printf("  %-22s %12s %12s %12s %12s\n", "input", "value", "range", "elasticity",
                s.sobol ? "ST" : "");
    for (size_t j = 0; j < s.inputs.size(); ++j) {
      std::printf("  %-22s %12.5g %11.3g%% %12.4g", s.inputs[j].name.c_str(), s.inputs[j].value,
                  100.0 * s.inputs[j].range, s.local.elasticity[c][j]);
      if (s.sobol) std::printf(" %12.3g", s.sobol->outputs[c].st[j]);
      std::printf("\n");
    }
    std::printf("  (%s = %.6g; written to %s)\n", args.chart.c_str(), s.local.f0[c], out.c_str());
  }
  return 0;
}

}  // namespace

int run_sensitivity(const SensitivityArgs& args) {
  // Every rank reads the options and the design, and fails the same way on bad input.
  auto load = [&] {
    options_of(args).validate();  // before reading the design: a bad option is the first error
    nlohmann::json design = io::read_json_file(args.design_path);
    optimize::read_design(design, args.design_path);
    return design;
  };
#ifdef PRONK_WITH_MPI
  if (optimize::mpi::mpi_launched()) {
    namespace mp = optimize::mpi;
    return run_on_mpi_ranks<nlohmann::json>(
        load, [](const nlohmann::json&) { mp::serve_evaluations(); },
        [&](const mp::MpiSession& session, const nlohmann::json& design) {
          mp::MpiJobFarm farm(session);
          const int rc = run_reporting_errors([&] { return run_loaded(args, design, &farm); });
          farm.release_workers();
          return rc;
        });
  }
#endif
  if (refuse_mpirun_without_mpi()) return 2;
  return run_loaded(args, load(), nullptr);
}

}  // namespace pronk::app
