#include "app/reproduce_command.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "app/optimize_command.hpp"
#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/moo_study.hpp"
#include "optimize/reproduce.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::app {

namespace {

using optimize::CompareMode;

// How the values are compared, in one line.
std::string mode_text(const optimize::ReproduceReport& rep) {
  char rtol[32];
  std::snprintf(rtol, sizeof rtol, "%g", rep.rtol);
  switch (rep.mode) {
    case CompareMode::kBitIdentical:
      return rep.same_build ? "the recording build: every value bit-identical"
                            : "--strict on the recording compiler and flags: every value "
                              "bit-identical";
    case CompareMode::kTolerance:
      return "another build: each value within the tolerance the design records for it "
             "(its perturbation run)";
    case CompareMode::kRelative:
      return std::string("each value within rtol ") + rtol +
             (rep.decisions_recorded ? "" : " (the design records no tolerances of its own)");
  }
  return "";
}

// (a) The per-trial decisions.
void print_decisions(const optimize::ReproduceReport& rep) {
  if (!rep.decisions_recorded) {
    std::printf(
        "(a) decisions: not compared: this design records no per-trial decisions (it was "
        "recorded before pronk recorded them)\n");
    return;
  }
  if (rep.decision_differences.empty()) {
    std::printf("(a) decisions of %s: identical\n",
                run::count_text(rep.trials_compared, "trial").c_str());
    return;
  }
  const long fragile = static_cast<long>(rep.decision_differences.size()) - rep.decision_mismatches;
  std::printf("(a) decisions of %s: %ld differ%s\n",
              run::count_text(rep.trials_compared, "trial").c_str(), rep.decision_mismatches,
              fragile > 0 ? (", and " + run::count_text(fragile, "fragile trial") +
                             " (not required: the recording's perturbation run "
                             "changed them too)")
                                .c_str()
                          : "");
  for (const auto& d : rep.decision_differences) {
    std::printf("  %s %s %ld (%s): recorded %s; reproduced %s\n",
                d.fragile ? "fragile " : "DIFFERS ", d.set.c_str(), d.index,
                d.recorded.name.c_str(), d.recorded.describe().c_str(),
                d.reproduced.describe().c_str());
  }
}

// (b) The recorded values.
void print_values(const optimize::ReproduceReport& rep) {
  std::printf("(b) values: %s\n", mode_text(rep).c_str());
  std::printf("  %-30s %22s %22s %10s %10s\n", "value", "recorded", "reproduced", "|diff|",
              "tolerance");
  for (const auto& v : rep.values) {
    std::printf("  %-30s %22.15g %22.15g %10.2e %10.2e  %s\n", v.name.c_str(), v.recorded,
                v.reproduced, std::abs(v.reproduced - v.recorded), v.tolerance,
                v.ok ? "ok" : "MISMATCH");
  }
}

// --rtol as given: a number (ReproduceOptions::validate checks its range); "" when absent.
std::optional<double> parse_rtol(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') {
    throw io::InputError("--rtol", "", "a finite relative tolerance > 0", "\"" + text + "\"");
  }
  return v;
}

}  // namespace

CLI::App* add_reproduce_command(CLI::App& app, ReproduceArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "reproduce",
      "Re-simulate a tuned design (design.json) and compare (a) every trial's decisions\n"
      "(fell, stabilized, apex held), which must be identical, and (b) every recorded value:\n"
      "bit-identical on the recording build (commit, compiler and flags), within the\n"
      "tolerance the design records for it on another build, or within --rtol.\n"
      "With --front-index K the file is a pareto.json (a multi-objective study) and front\n"
      "design K is reproduced: bit-identical on the recording build, else within --rtol\n"
      "(default 1e-6: front designs record no tolerances of their own).");
  cmd->add_option("design", args.design_path,
                  "design.json written by pronk optimize (pareto.json with --front-index)")
      ->required();
  cmd->add_option("--front-index", args.front_index,
                  "Reproduce design K of a pareto.json's front (its \"index\", the first "
                  "column of pareto.csv)")
      ->type_name("K")
      ->check(CLI::Range(0L, 100000000L));
  cmd->add_option("--threads", args.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--rtol", args.rtol,
                  "Compare every value at this relative tolerance instead of the design's own "
                  "tolerances")
      ->type_name("R");
  cmd->add_flag("--strict", args.strict,
                "Bit-identical also on a later commit when the compiler and flags are the "
                "recording build's (CI: a change that moves numbers must re-record)");
  cmd->add_flag("--scenarios-only", args.scenarios_only,
                "Re-evaluate the study's scenarios only, not its validation set");
  return cmd;
}

int run_reproduce(const ReproduceArgs& args) {
  optimize::ReproduceOptions opt;
  opt.threads = thread_count(args.threads);
  opt.rtol = parse_rtol(args.rtol);
  opt.strict = args.strict;
  opt.scenarios_only = args.scenarios_only;
  opt.validate();  // before reading the design: a bad option is the first error
  const nlohmann::json design = io::read_json_file(args.design_path);
  if (args.front_index < 0 && design.is_object() && design.value("type", "") == "pronk_pareto") {
    throw io::InputError(args.design_path, "/type",
                         "\"pronk_design\" (a design.json; a pareto.json needs --front-index K)",
                         "string \"pronk_pareto\"");
  }
  const optimize::ReproduceReport rep =
      args.front_index >= 0
          ? optimize::reproduce_front_design(design, args.design_path, args.front_index, opt)
          : optimize::reproduce_design(design, args.design_path, opt);
  if (args.front_index >= 0) std::printf("front design %ld of:\n", args.front_index);
  std::printf("reproducing %s\n  recorded by: %s\n  this build:  %s\n", args.design_path.c_str(),
              rep.recorded_build.c_str(), rep.this_build.c_str());
  if (rep.validation_skipped) {
    std::printf("  the validation set is not re-evaluated (--scenarios-only)\n");
  }
  print_decisions(rep);
  print_values(rep);
  const long fragile = static_cast<long>(rep.decision_differences.size()) - rep.decision_mismatches;
  std::string decisions = "decisions not recorded";
  if (rep.decisions_recorded) {
    decisions = std::to_string(rep.decision_mismatches) + " of " +
                std::to_string(rep.trials_compared) + " trial decisions differ";
    if (fragile > 0) decisions += " (and " + std::to_string(fragile) + " fragile ones)";
  }
  std::printf("%s: %ld of %zu values differ%s (%ld bit-identical); %s\n",
              rep.reproduced() ? "reproduced" : "NOT REPRODUCED", rep.mismatches, rep.values.size(),
              rep.mode == CompareMode::kBitIdentical ? "" : " beyond tolerance", rep.bit_identical,
              decisions.c_str());
  return rep.reproduced() ? 0 : 1;
}

}  // namespace pronk::app
