#include "optimize/thread_pool.hpp"

namespace pronk::optimize {

namespace {
// About 50-100 microseconds of polling before a worker goes to sleep.
constexpr int kSpinIterations = 20000;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}
}  // namespace

ThreadPool::ThreadPool(int threads) {
  for (int i = 1; i < threads; ++i) workers_.emplace_back([this] { worker(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_.store(true);
  }
  cv_.notify_all();
  for (auto& w : workers_) w.join();
}

void ThreadPool::run_items(Job& job) {
  for (long i = job.next.fetch_add(1); i < job.n; i = job.next.fetch_add(1)) {
    (*job.fn)(i);
    job.done.fetch_add(1, std::memory_order_release);
  }
}

void ThreadPool::worker() {
  long seen = 0;
  for (;;) {
    int spins = 0;
    while (generation_.load(std::memory_order_acquire) == seen && !stop_.load()) {
      if (++spins < kSpinIterations) {
        cpu_relax();
        continue;
      }
      std::unique_lock<std::mutex> lock(m_);
      cv_.wait(lock, [&] { return generation_.load() != seen || stop_.load(); });
    }
    if (stop_.load()) return;
    std::shared_ptr<Job> job;
    {
      std::lock_guard<std::mutex> lock(m_);
      seen = generation_.load();
      job = job_;  // a late worker holds the old, finished job: no items left in it
    }
    if (job) run_items(*job);
  }
}

void ThreadPool::parallel_for(long n, const std::function<void(long)>& fn) {
  std::unique_lock<std::mutex> exclusive(job_mutex_, std::try_to_lock);
  if (!exclusive.owns_lock() || workers_.empty() || n <= 1) {
    for (long i = 0; i < n; ++i) fn(i);
    return;
  }
  auto job = std::make_shared<Job>();
  job->fn = &fn;
  job->n = n;
  {
    std::lock_guard<std::mutex> lock(m_);
    job_ = job;
    generation_.fetch_add(1, std::memory_order_release);
  }
  cv_.notify_all();
  run_items(*job);
  while (job->done.load(std::memory_order_acquire) < n) cpu_relax();
  // Workers that still hold `job` find no items left; fn outlives nothing they run.
}

}  // namespace pronk::optimize
