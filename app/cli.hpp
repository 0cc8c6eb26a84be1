// The pronk command line (CLI11): subcommands, exit codes 0 (success), 1 (a run
// or check failed), 2 (bad input).
#pragma once

#include <functional>
#include <iosfwd>

namespace pronk::app {

/// Runs the CLI; returns the process exit code. Never throws.
int run_cli(int argc, const char* const* argv);

/// Runs `body`, turning an io::InputError into "pronk: error: ..." (exit code 2) and any
/// other exception into "pronk: failed: ..." (1) on stderr; otherwise returns body's code.
int run_reporting_errors(const std::function<int()>& body);

}  // namespace pronk::app
