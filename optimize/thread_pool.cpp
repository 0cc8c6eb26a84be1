#include "optimize/thread_pool.hpp"

namespace pronk::optimize {

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { worker(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  for (auto& w : workers_) w.join();
}

void ThreadPool::worker() {
  long seen = 0;
  for (;;) {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    ++active_;
    while (next_ < n_) {
      const long i = next_++;
      lock.unlock();
      (*fn_)(i);
      lock.lock();
      ++finished_;
    }
    --active_;
    done_cv_.notify_all();
  }
}

void ThreadPool::parallel_for(long n, const std::function<void(long)>& fn) {
  std::unique_lock<std::mutex> job(job_mutex_, std::try_to_lock);
  if (!job.owns_lock() || workers_.empty() || n <= 1) {
    for (long i = 0; i < n; ++i) fn(i);
    return;
  }
  std::unique_lock<std::mutex> lock(m_);
  fn_ = &fn;
  n_ = n;
  next_ = 0;
  finished_ = 0;
  ++generation_;
  cv_.notify_all();
  while (next_ < n_) {
    const long i = next_++;
    lock.unlock();
    fn(i);
    lock.lock();
    ++finished_;
  }
  done_cv_.wait(lock, [&] { return finished_ == n_ && active_ == 0; });
  fn_ = nullptr;
  n_ = 0;
}

}  // namespace pronk::optimize
