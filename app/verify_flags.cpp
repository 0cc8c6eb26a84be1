#include "app/verify_flags.hpp"

#include <cstdio>
#include <random>

#include "io/load/input_error.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::app {

void add_verify_flags(CLI::App* cmd, VerifyArgs& args) {
  cmd->add_option("--verify", args.sample,
                  "With --resume: evaluate every journal record again (or a seeded sample of N) "
                  "and refuse any that differs")
      ->expected(0, 1)
      ->default_str("0")
      ->type_name("[N]")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--verify-seed", args.seed, "Seed of the --verify N sample (default: fresh)")
      ->each([&args](const std::string&) { args.seed_given = true; });
}

std::uint64_t verify_seed(const VerifyArgs& args, bool resume, bool quiet) {
  if ((args.sample >= 0 || args.seed_given) && !resume) {
    throw io::InputError(args.sample >= 0 ? "--verify" : "--verify-seed", "",
                         "--resume with it (it checks the journal being resumed)", "no --resume");
  }
  if (args.seed_given || args.sample <= 0) return args.seed;
  const std::uint64_t seed =
      (static_cast<std::uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
  if (!quiet)
    std::fprintf(stderr, "pronk: verifying %s drawn with --verify-seed %llu\n",
                 run::count_text(args.sample, "journal record").c_str(),
                 static_cast<unsigned long long>(seed));
  return seed;
}

}  // namespace pronk::app
