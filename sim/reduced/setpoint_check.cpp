#include "sim/reduced/setpoint_check.hpp"

#include <cmath>

namespace pronk::reduced {

SetpointCheck check_setpoint(const scene::Scene& scene, const RunResult& run,
                             const RunMetrics& metrics) {
  SetpointCheck c;
  c.distance = std::hypot(metrics.final_x_error, metrics.final_y_error);
  c.hop_heights = c.distance / scene.controller.hop_height;
  const bool completed = run.status == RunStatus::kCompleted;
  c.far = completed && c.hop_heights > kFarFromSetpointHopHeights;
  c.never_settled = completed && metrics.settle_strides < 0;
  return c;
}

void add_setpoint_warnings(const SetpointCheck& check, std::map<std::string, long>* warnings) {
  if (check.far) (*warnings)["far_from_setpoint"] = 1;
  if (check.never_settled) (*warnings)["never_settled"] = 1;
}

}  // namespace pronk::reduced
