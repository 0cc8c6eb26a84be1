// A Progress (progress.hpp) that several worker threads advance together: each finished item
// counts once, whichever thread finished it.
#pragma once

#include <mutex>
#include <string>

#include "optimize/progress.hpp"

namespace pronk::optimize {

class SharedProgress {
 public:
  SharedProgress(ProgressStyle style, std::string label, long total);
  SharedProgress(const SharedProgress&) = delete;
  SharedProgress& operator=(const SharedProgress&) = delete;

  /// One more item done (thread-safe).
  void add();
  /// At least `done` items done (thread-safe): for work that reports only whole batches.
  void reach(long done);
  /// Ends a terminal's line.
  void finish();

 private:
  std::mutex m_;
  Progress progress_;
  long done_ = 0;
};

}  // namespace pronk::optimize
