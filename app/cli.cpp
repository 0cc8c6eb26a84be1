#include "app/cli.hpp"

#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/bench_command.hpp"
#include "app/compare_command.hpp"
#include "app/design_command.hpp"
#include "app/map_command.hpp"
#include "app/optimize_command.hpp"
#include "app/reproduce_command.hpp"
#include "app/sensitivity_command.hpp"
#include "app/simulate_command.hpp"
#include "app/view_command.hpp"
#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/plot.hpp"

namespace pronk::app {

namespace {

// A command-line error (an unknown flag, --threads 0) as the one line of any bad input,
// instead of CLI11's two; exit code 2.
int report_option_error(const CLI::ParseError& e) {
  std::string what = e.what();
  for (char& c : what) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!what.empty() && what.back() == ' ') what.pop_back();
  const io::InputError error("command line", "", "options as `pronk COMMAND --help` lists them",
                             what);
  std::cerr << "pronk: error: " << error.what() << "\n";
  return 2;
}

}  // namespace

int run_cli(int argc, const char* const* argv) {
  CLI::App app{
      "pronk: design and simulate robots that run by ballistic hops.\n"
      "Exit codes: 0 success, 1 a run or check failed, 2 bad input."};
  app.set_version_flag("--version",
                       std::string(pronk::version()) + " (" + pronk::git_commit() + ")");
  app.require_subcommand(1);
  SimulateArgs simulate_args;
  CLI::App* simulate = add_simulate_command(app, simulate_args);
  OptimizeArgs optimize_args;
  CLI::App* optimize = add_optimize_command(app, optimize_args);
  ReproduceArgs reproduce_args;
  CLI::App* reproduce = add_reproduce_command(app, reproduce_args);
  SensitivityArgs sensitivity_args;
  CLI::App* sensitivity = add_sensitivity_command(app, sensitivity_args);
  MapArgs map_args;
  CLI::App* map = add_map_command(app, map_args);
  ViewArgs view_args;
  CLI::App* view = add_view_command(app, view_args);
  CompareArgs compare_args;
  CLI::App* compare = add_compare_command(app, compare_args);
  DesignArgs design_args;
  CLI::App* design = add_design_command(app, design_args);
  BenchArgs bench_args;
  CLI::App* bench = add_bench_command(app, bench_args);
  // Every command that draws figures can skip gnuplot: the data and the .gp scripts stay.
  bool no_figures = false;
  for (CLI::App* cmd : {simulate, optimize, reproduce, design, map, compare, sensitivity}) {
    cmd->add_flag("--no-figures", no_figures,
                  "Write the CSV data and gnuplot scripts but render no SVG figures (faster; "
                  "`gnuplot NAME.gp` in the output directory renders one later)");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return report_option_error(e);
  }
  io::set_render_figures(!no_figures);
  return run_reporting_errors([&] {
    // Every command's --out is checked before any work: a path that cannot be a
    // directory is bad input, not a failure after the run.
    for (const CLI::App* cmd : app.get_subcommands()) {
      const CLI::Option* out = cmd->get_option_no_throw("--out");
      if (out != nullptr && out->count() > 0) {
        io::check_output_directory(out->as<std::string>(), "--out");
      }
    }
    if (simulate->parsed()) return run_simulate(simulate_args);
    if (optimize->parsed()) return run_optimize(optimize_args);
    if (reproduce->parsed()) return run_reproduce(reproduce_args);
    if (compare->parsed()) return run_compare(compare_args);
    if (sensitivity->parsed()) return run_sensitivity(sensitivity_args);
    if (design->parsed()) return run_design(design_args);
    if (map->parsed()) return run_map_command(map_args);
    if (view->parsed()) return run_view(view_args);
    if (bench->parsed()) return run_bench(bench_args);
    return 2;
  });
}

int run_reporting_errors(const std::function<int()>& body) {
  try {
    return body();
  } catch (const io::InputError& e) {
    std::cerr << "pronk: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pronk: failed: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace pronk::app
