// Metrics of one run (docs/studies.md), computed from its records: what a user or an
// optimizer judges a gait by. Never NaN: quantities without data are 0 and
// flagged by the counts.
#pragma once

#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

/// Thresholds that define "settled" [m, m, rad, m].
struct SettleCriteria {
  double position_error = 0.01;    ///< |x - x_d|, |y - y_d| at touchdown [m]
  double tilt = 1.0 * M_PI / 180;  ///< |roll|, |pitch| at touchdown [rad]
  double apex_error = 0.005;       ///< |apex - (l + h)| [m]
};

struct RunMetrics {
  long strides = 0;                            ///< touchdowns
  double final_x_error = 0.0;                  ///< x - x_d at the end of the run [m]
  double final_y_error = 0.0;                  ///< y - y_d at the end of the run [m]
  double final_roll = 0.0, final_pitch = 0.0;  ///< 1-2-3 angles at the end [rad]
  double max_apex_error = 0.0;   ///< max |apex - (l + h)| over strides after the first [m]
  double last_apex_error = 0.0;  ///< apex - (l + h) of the last stride with an apex [m]
  double mean_duty = 0.0, max_duty = 0.0;  ///< over complete strides [-]
  double max_tilt = 0.0;                   ///< max tilt of body z from vertical at touchdowns [rad]
  double peak_leg_force = 0.0;             ///< [N]
  double mean_impulse_per_stride = 0.0;    ///< mean |P_delivered| [N s]
  long settle_strides = -1;  ///< first stride after which all criteria hold; -1: never
};

RunMetrics compute_metrics(const scene::Scene& scene, const RunResult& run,
                           const SettleCriteria& criteria = {});

}  // namespace pronk::reduced
