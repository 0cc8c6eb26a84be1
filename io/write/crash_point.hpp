// A deterministic crash for the kill-and-resume tests. With the environment variable
// PRONK_CRASH_AT=N (N >= 1) the process ends at once (std::_Exit(86): no destructors, no
// flush, as kill -9 would leave it) at the N-th crash point it reaches; the points are
// placed where a real kill does the most harm (a temporary written and not yet renamed,
// half a journal line written). With PRONK_CRASH_AT=0 nothing crashes and the number of
// points reached is printed to stderr at exit ("pronk: crash points: K"), so a test can
// draw N from 1..K. Unset (always, outside tests): one relaxed atomic load per point.
#pragma once

namespace pronk::io {

/// The exit code of a crash point.
inline constexpr int kCrashExitCode = 86;

/// Counts one crash point; ends the process when it is the one PRONK_CRASH_AT names.
void crash_point();

/// Whether the next crash point ends the process (to tear a write in half first).
bool crash_point_is_next();

}  // namespace pronk::io
