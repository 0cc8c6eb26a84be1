#include "optimize/job_schedule.hpp"

#include <algorithm>
#include <numeric>

namespace pronk::optimize {

std::vector<long> JobSchedule::order(long n) const {
  std::vector<long> idx(static_cast<size_t>(std::max(0L, n)));
  std::iota(idx.begin(), idx.end(), 0L);
  std::lock_guard<std::mutex> lock(m_);
  if (static_cast<long>(seconds_.size()) != n) return idx;
  std::stable_sort(idx.begin(), idx.end(), [&](long a, long b) {
    return seconds_[static_cast<size_t>(a)] > seconds_[static_cast<size_t>(b)];
  });
  return idx;
}

void JobSchedule::record(std::vector<double> seconds) {
  std::lock_guard<std::mutex> lock(m_);
  seconds_ = std::move(seconds);
}

}  // namespace pronk::optimize
