// The order an evaluation starts its jobs in. The jobs of one evaluation differ in length
// (a trial that falls early ends early; one that auto reruns tighter costs 1.3-2x one that
// does not), and one started last that runs long leaves the other threads idle. The
// schedule starts the jobs longest first, by the durations the previous evaluation measured:
// neighbouring parameter points run the same scenarios, and a scenario that ran long (rerun,
// or a long stance) tends to run long again. Only the schedule depends on the clock: each
// job writes its own result slot, so the numbers are the same in any order.
#pragma once

#include <mutex>
#include <vector>

namespace pronk::optimize {

class JobSchedule {
 public:
  /// The order in which to start n jobs: longest first by the last recorded durations (ties
  /// and unmeasured jobs in index order); index order when no evaluation of n jobs has been
  /// recorded. Thread-safe.
  std::vector<long> order(long n) const;
  /// Records the durations [s] of an evaluation's jobs, by job index. Thread-safe.
  void record(std::vector<double> seconds);

 private:
  mutable std::mutex m_;
  std::vector<double> seconds_;
};

}  // namespace pronk::optimize
