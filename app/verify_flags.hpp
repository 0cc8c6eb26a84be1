// `--verify [N]` and `--verify-seed S` of `pronk optimize` and `pronk map`: with --resume,
// evaluate the journal's records again (every record, or a seeded sample of N) and refuse
// any that differs (optimize/journal_check.hpp, optimize/map/map_journal.hpp).
#pragma once

#include <cstdint>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct VerifyArgs {
  long sample = -1;  ///< -1: no --verify; 0: --verify (every record); N: --verify N
  std::uint64_t seed = 0;
  bool seed_given = false;
};

/// Adds --verify [N] and --verify-seed S to `cmd`.
void add_verify_flags(CLI::App* cmd, VerifyArgs& args);

/// The seed of the sample: --verify-seed, or a fresh one, printed to stderr unless `quiet`
/// so that the same sample can be drawn again. io::InputError when --verify or
/// --verify-seed comes without --resume.
std::uint64_t verify_seed(const VerifyArgs& args, bool resume, bool quiet);

}  // namespace pronk::app
