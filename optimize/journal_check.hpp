// Checks of a study journal against the study on --resume. Evaluations are deterministic,
// so a record evaluated again gives the same bytes: the last record always is (a journal
// of another build or a forged tail is refused), and `--verify` evaluates every record or
// a seeded sample, which also catches a forger who recomputed the checksum chain.
#pragma once

#include <cstdint>
#include <string>

#include "optimize/evaluator.hpp"
#include "optimize/journal.hpp"

namespace pronk::optimize {

/// Throws io::InputError at `path`, naming the line and the first key that differs, unless
/// the journal's last record is what evaluating its point again gives.
void check_last_record(const JournalContents& journal, const Evaluator& ev,
                       const std::string& path);

/// Evaluates the records verification_sample(records, sample, seed) picks (sample <= 0:
/// every record) again, in batches over the evaluator's threads; throws io::InputError for
/// the first (by line) that differs. Returns how many were evaluated.
long verify_records(const JournalContents& journal, const Evaluator& ev, long sample,
                    std::uint64_t seed, const std::string& path);

}  // namespace pronk::optimize
