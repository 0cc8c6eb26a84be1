// The thread pool: every index exactly once, work really shared, nested calls inline.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "optimize/thread_pool.hpp"

using pronk::optimize::ThreadPool;

TEST_CASE("parallel_for visits every index once and shares the work", "[optimize][threads]") {
  for (int threads : {1, 2, 4}) {
    ThreadPool pool(threads);
    CHECK(pool.threads() == threads);
    for (int round = 0; round < 3; ++round) {
      std::vector<std::atomic<int>> hits(50);
      std::mutex m;
      std::set<std::thread::id> ids;
      pool.parallel_for(50, [&](long i) {
        hits[static_cast<size_t>(i)]++;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        std::lock_guard<std::mutex> lock(m);
        ids.insert(std::this_thread::get_id());
      });
      for (auto& h : hits) CHECK(h.load() == 1);
      // Items sleep, so the workers get a share even on a loaded machine.
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
