// The journal of a map (optimize/journal.hpp's format: chained checksums): a header with the
// study's hash, then one record per finished cell and, once every cell is done, one per
// bisected row. On --resume every record is checked against the study and its neighbours:
//   - a cell: its index in the grid and recorded once; one list of trials per model, each
//     of the study's trial count; every trial consistent in itself (a status the simulator
//     gives, settle and stride counts that fit, "stabilized" exactly the study's rule); a
//     spectral radius exactly when the cell owns its scene's stability;
//   - a row's boundary: after every cell, the row recorded once, the row's cells bracketing
//     a boundary, and the final bracket one the bisection from that bracket reaches in the
//     recorded number of probes, with the boundary its good end.
// The last cell is computed again (cells are deterministic); with verify, a sample of the
// records or all of them. What consistency cannot catch (a forged but consistent record,
// its chain recomputed) only that re-computation does.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "optimize/journal.hpp"
#include "optimize/map/map_engine.hpp"
#include "optimize/map/map_runner.hpp"

namespace pronk::optimize::map {

/// What a map journal holds.
struct MapJournalState {
  bool exists = false;  ///< a header was read
  std::map<long, CellResult> cells;
  std::map<long, BoundaryResult> boundaries;
  std::map<long, long> cell_lines, boundary_lines;  ///< cell / row -> its 1-based line
  long last_cell = -1;                              ///< the last cell recorded (-1: none)
  JournalEnd end;                                   ///< for prepare_for_append
};

/// The header of the journal of `st`.
nlohmann::json map_journal_header(const MapStudy& st);

/// Reads and checks the journal of `st` at `path` (empty state when there is none): the
/// checksum chain, the header's hash, and every record as the file comment says.
/// io::InputError naming the line and what does not fit.
MapJournalState read_map_journal(const std::string& path, const MapStudy& st);

/// Computes the last cell again, and the records verification_sample(records, sample,
/// seed) picks when sample >= 0 (0: all), on `runner`; io::InputError for the first one (by
/// line) that differs. Returns how many records were computed for the sample.
long verify_map_journal(const MapJournalState& js, const MapStudy& st, TaskRunner& runner,
                        long sample, std::uint64_t seed, const std::string& path);

}  // namespace pronk::optimize::map
