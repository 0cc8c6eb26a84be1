#include "sim/robot/fidelity.hpp"

#include <algorithm>
#include <cmath>

namespace pronk::robot {

FidelityDiscrepancy compare_strides(const reduced::RunResult& a, const reduced::RunResult& b,
                                    size_t max_strides) {
  FidelityDiscrepancy d;
  const size_t n = std::min({a.strides.size(), b.strides.size(), max_strides});
  d.strides = static_cast<long>(n);
  for (size_t k = 0; k < n; ++k) {
    const auto &sa = a.strides[k], &sb = b.strides[k];
    if (sa.has_apex && sb.has_apex) {
      d.max_apex = std::max(d.max_apex, std::abs(sa.apex_height - sb.apex_height));
      if (sb.apex_height > 0.0) {
        d.max_apex_relative = std::max(d.max_apex_relative,
                                       std::abs(sa.apex_height - sb.apex_height) / sb.apex_height);
      }
    }
    if (sb.stance_duration > 0.0) {
      d.max_stance_relative =
          std::max(d.max_stance_relative,
                   std::abs(sa.stance_duration - sb.stance_duration) / sb.stance_duration);
    }
    d.max_attitude = std::max(d.max_attitude, (sa.euler123 - sb.euler123).cwiseAbs().maxCoeff());
    d.max_touchdown_position =
        std::max(d.max_touchdown_position, (sa.position - sb.position).norm());
  }
  return d;
}

}  // namespace pronk::robot
