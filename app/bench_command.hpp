// `pronk bench`: the speed-versus-accuracy measurements of docs/performance.md in one run —
// work-precision of every solver (and internal stiffness), the fidelity ladder,
// the quad hopper drop, and the optional peers (SUNDIALS CVODE, MuJoCo), which
// are separate executables built only when their libraries are found: `pronk
// bench` runs the ones that sit beside it and merges their JSON into bench.json. The groups
// live in app/bench/ (suite.hpp), one file each.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct BenchArgs {
  bool quick = false;  ///< CI size (< 1 min)
  std::string out_dir = "out/bench";
  int repeat = 0;           ///< timed repeats per point (median); 0 = 3, or 1 with --quick
  bool no_peers = false;    ///< skip the peer executables even when built
  std::string studies_dir;  ///< the shipped studies/ directory; default: the source tree's
  bool quiet = false;
  /// "" runs everything; "auto" only the check of "method": "auto" (app/bench/auto_check.hpp), into
  /// DIR/auto_check.json (bench.json untouched).
  std::string only;
};

CLI::App* add_bench_command(CLI::App& app, BenchArgs& args);
/// Runs the benchmark; returns the exit code (0 ok, 1 a peer failed, 2 bad input).
int run_bench(const BenchArgs& args);

}  // namespace pronk::app
