// A small fixed pool of worker threads with a deterministic parallel_for:
// results are written by index, so the outcome does not depend on the thread
// count or on scheduling.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace pronk::optimize {

class ThreadPool {
 public:
  /// threads <= 1: no workers, parallel_for runs inline.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  /// Calls fn(i) for i in [0, n), spread over the workers and the calling
  /// thread. A call made while another is running (nested or concurrent) runs
  /// inline. fn must not throw.
  void parallel_for(long n, const std::function<void(long)>& fn);

 private:
  void worker();
  std::vector<std::thread> workers_;
  std::mutex job_mutex_;  // one parallel_for at a time
  std::mutex m_;
  std::condition_variable cv_, done_cv_;
  const std::function<void(long)>* fn_ = nullptr;
  long n_ = 0, next_ = 0, finished_ = 0;
  long generation_ = 0;
  int active_ = 0;
  bool stop_ = false;
};

}  // namespace pronk::optimize
