// What the optimizer benchmarks (bench_pagmo, bench_moo) measure beside wall time: the
// process's CPU time (the cores a run really had) and the machine's load average.
#pragma once

#include <ctime>
#include <fstream>

namespace pronk::bench {

/// The 1-minute load average (/proc/loadavg), or -1 when unreadable.
inline double load_average() {
  std::ifstream in("/proc/loadavg");
  double one = -1.0;
  in >> one;
  return one;
}

/// CPU seconds of this process, all threads.
inline double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace pronk::bench
