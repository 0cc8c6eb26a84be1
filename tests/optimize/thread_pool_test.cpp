// The thread pool: every index exactly once, work really shared, nested calls inline.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "optimize/thread_pool.hpp"

using pronk::optimize::ThreadPool;

TEST_CASE("parallel_for visits every index once and shares the work", "[optimize][threads]") {
  // No sleep and no clock: with more than one thread, every item waits until a second
  // thread has taken an item. A pool that shares the work passes whatever the scheduling;
  // one that runs every item on one thread leaves the first item waiting until the 60 s
  // safety limit, and the check below fails.
  for (int threads : {1, 2, 4}) {
    ThreadPool pool(threads);
    CHECK(pool.threads() == threads);
    for (int round = 0; round < 3; ++round) {
      std::vector<std::atomic<int>> hits(50);
      std::mutex m;
      std::condition_variable second_thread;
      std::set<std::thread::id> ids;
      pool.parallel_for(50, [&](long i) {
        hits[static_cast<size_t>(i)]++;
        std::unique_lock<std::mutex> lock(m);
        ids.insert(std::this_thread::get_id());
        second_thread.notify_all();
        if (threads > 1)
          second_thread.wait_for(lock, std::chrono::seconds(60), [&] { return ids.size() >= 2; });
      });
      for (auto& h : hits) CHECK(h.load() == 1);
      if (threads > 1)
        CHECK(ids.size() >= 2);
      else
        CHECK(ids.size() == 1);
    }
  }
}

TEST_CASE("a nested parallel_for runs inline", "[optimize][threads]") {
  ThreadPool pool(2);
  std::atomic<long> sum{0};
  pool.parallel_for(4, [&](long i) { pool.parallel_for(3, [&](long j) { sum += 10 * i + j; }); });
  // sum over i<4, j<3 of (10 i + j) = 3 * 10 * 6 + 4 * 3 = 192
  CHECK(sum.load() == 192);
}
