#include "sim/reduced/metrics.hpp"

#include <algorithm>
#include <cmath>

#include "sim/math/rotation.hpp"

namespace pronk::reduced {

RunMetrics compute_metrics(const scene::Scene& scene, const RunResult& run,
                           const SettleCriteria& criteria) {
  RunMetrics m;
  m.strides = run.cost.touchdowns;
  const Eigen::Vector3d x_d =
      scene.controller.setpoint_position + scene.controller.setpoint_velocity * run.t_end;
  m.final_x_error = run.final_position.x() - x_d.x();
  m.final_y_error = run.final_position.y() - x_d.y();
  m.final_roll = run.final_euler123.x();
  m.final_pitch = run.final_euler123.y();
  const double target_apex = scene.legs.length + scene.controller.hop_height;
  long complete = 0;
  double impulse_sum = 0.0;
  long last_unsettled = -1;
  for (const auto& s : run.strides) {
    if (s.has_apex) {
      m.last_apex_error = s.apex_height - target_apex;
      if (s.index > 0) m.max_apex_error = std::max(m.max_apex_error, std::abs(m.last_apex_error));
    }
    if (s.stride_time > 0.0) {
      ++complete;
      m.mean_duty += s.duty_cycle;
      m.max_duty = std::max(m.max_duty, s.duty_cycle);
    }
    const Eigen::Matrix3d R = math::euler_to_matrix(s.euler123, math::EulerSet::k123);
    m.max_tilt = std::max(m.max_tilt, std::acos(std::clamp(R(2, 2), -1.0, 1.0)));
    m.peak_leg_force = std::max(m.peak_leg_force, s.peak_leg_force);
    impulse_sum += s.P_delivered.norm();
    const bool settled =
        std::abs(s.position.x() - s.setpoint.x()) < criteria.position_error &&
        std::abs(s.position.y() - s.setpoint.y()) < criteria.position_error &&
        std::abs(s.euler123.x()) < criteria.tilt && std::abs(s.euler123.y()) < criteria.tilt &&
        (!s.has_apex || std::abs(s.apex_height - target_apex) < criteria.apex_error);
    if (!settled) last_unsettled = s.index;
  }
  if (complete > 0) m.mean_duty /= static_cast<double>(complete);
  if (!run.strides.empty())
    m.mean_impulse_per_stride = impulse_sum / static_cast<double>(run.strides.size());
  const bool ended_well = run.status == RunStatus::kCompleted;
  if (ended_well && !run.strides.empty() &&
      last_unsettled + 1 < static_cast<long>(run.strides.size())) {
    m.settle_strides = last_unsettled + 1;
  }
  return m;
}

}  // namespace pronk::reduced
