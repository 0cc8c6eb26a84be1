// A small fixed pool of worker threads with a deterministic parallel_for:
// results are written by index, so the outcome does not depend on the thread
// count or on scheduling. Idle workers spin briefly before sleeping, so the
// back-to-back short jobs of an optimization do not pay a wake-up each time.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
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
  struct Job {
    const std::function<void(long)>* fn = nullptr;
    long n = 0;
    std::atomic<long> next{0};
    std::atomic<long> done{0};
  };
  void worker();
  static void run_items(Job& job);

  std::vector<std::thread> workers_;
  std::mutex job_mutex_;  // one parallel_for at a time
  std::mutex m_;          // guards job_ and the sleep/wake protocol
  std::condition_variable cv_;
  std::shared_ptr<Job> job_;
  std::atomic<long> generation_{0};
  std::atomic<bool> stop_{false};
};

}  // namespace pronk::optimize
