#include "io/write/crash_point.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace pronk::io {

namespace {

std::atomic<long> g_reached{0};

// PRONK_CRASH_AT: -1 when unset (or not a number), else N.
long crash_at() {
  static const long n = [] {
    const char* v = std::getenv("PRONK_CRASH_AT");
    if (v == nullptr || *v == '\0') return -1L;
    char* end = nullptr;
    const long x = std::strtol(v, &end, 10);
    if (*end != '\0' || x < 0) return -1L;
    if (x == 0) {
      std::atexit([] { std::fprintf(stderr, "pronk: crash points: %ld\n", g_reached.load()); });
    }
    return x;
  }();
  return n;
}

}  // namespace

void crash_point() {
  const long n = crash_at();
  if (n < 0) return;
  if (g_reached.fetch_add(1) + 1 == n) std::_Exit(kCrashExitCode);
}

bool crash_point_is_next() {
  const long n = crash_at();
  return n > 0 && g_reached.load() + 1 == n;
}

}  // namespace pronk::io
