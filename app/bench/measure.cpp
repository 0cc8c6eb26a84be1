// The shared measurement helpers of `pronk bench`: thread CPU time, medians, cost columns.
#include "app/bench/measure.hpp"

#include <ctime>

namespace pronk::app::bench {

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void add_cost(nlohmann::json& row, const Cost& c) {
  row["wall_s"] = c.wall_s;
  row["cpu_s"] = c.cpu_s;
  row["steps"] = c.steps;
  row["rejected"] = c.rejected;
  row["rhs"] = c.rhs;
  row["jacobians"] = c.jacobians;
  row["lu"] = c.lu;
}

}  // namespace pronk::app::bench
