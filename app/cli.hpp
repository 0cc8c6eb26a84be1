// The pronk command line (CLI11): subcommands, exit codes 0 (success), 1 (a run
// or check failed), 2 (bad input).
#pragma once

#include <iosfwd>

namespace pronk::app {

/// Runs the CLI; returns the process exit code. Never throws.
int run_cli(int argc, const char* const* argv);

}  // namespace pronk::app
