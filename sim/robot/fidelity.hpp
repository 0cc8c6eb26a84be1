// Stride-by-stride comparison of two runs of the same robot at different
// fidelities (e.g. pulse vs pseudo-rigid): the discrepancy the summary reports.
#pragma once

#include "sim/reduced/run_result.hpp"

namespace pronk::robot {

struct FidelityDiscrepancy {
  long strides = 0;                     ///< strides compared (both runs have them)
  double max_apex = 0.0;                ///< max |apex_a - apex_b| [m]
  double max_attitude = 0.0;            ///< max |euler123_a - euler123_b| at touchdown [rad]
  double max_touchdown_position = 0.0;  ///< max |x_a - x_b| at touchdown [m]
  double max_apex_relative = 0.0;       ///< max |apex_a - apex_b| / apex_b [-]
  double max_stance_relative = 0.0;     ///< max |stance_a - stance_b| / stance_b [-]
};

/// The discrepancy of a against b (the reference) over their first max_strides common strides.
FidelityDiscrepancy compare_strides(const reduced::RunResult& a, const reduced::RunResult& b,
                                    size_t max_strides = static_cast<size_t>(-1));

}  // namespace pronk::robot
