// `pronk map STUDY.json [--threads N] [--resume] [--out DIR] [--set /ptr=value]... [--quiet]`:
// a robustness map of a design (docs/maps.md), on threads or, under mpirun, on MPI ranks.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/verify_flags.hpp"

namespace pronk::app {

struct MapArgs {
  std::string study_path;
  int threads = 0;  ///< 0: all hardware threads (one per rank under MPI)
  bool resume = false;
  VerifyArgs verify;
  std::string out_dir;
  std::vector<std::string> overrides;
  bool quiet = false;
};

CLI::App* add_map_command(CLI::App& app, MapArgs& args);

/// 0: the map is complete and written; 1: interrupted (journal kept) or failed.
int run_map_command(const MapArgs& args);

}  // namespace pronk::app
