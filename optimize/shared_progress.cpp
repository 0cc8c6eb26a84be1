#include "optimize/shared_progress.hpp"

#include <utility>

namespace pronk::optimize {

SharedProgress::SharedProgress(ProgressStyle style, std::string label, long total)
    : progress_(style, std::move(label), total) {}

void SharedProgress::add() {
  const std::lock_guard<std::mutex> lock(m_);
  progress_.update(++done_);
}

void SharedProgress::reach(long done) {
  const std::lock_guard<std::mutex> lock(m_);
  if (done <= done_) return;
  done_ = done;
  progress_.update(done_);
}

void SharedProgress::finish() {
  const std::lock_guard<std::mutex> lock(m_);
  progress_.finish();
}

}  // namespace pronk::optimize
