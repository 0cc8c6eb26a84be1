#include "sim/control/leg_controller.hpp"

#include <algorithm>

namespace pronk::control {

double PulseLegController::stance_duration(const std::vector<Eigen::Vector3d>& p) const {
  if (pulse_.mode == scene::PulseMode::kDuration) return pulse_.duration;
  double largest = 0.0;
  for (const auto& pi : p) largest = std::max(largest, pi.norm());
  return largest / pulse_.max_force;
}

std::unique_ptr<LegController> make_leg_controller(const scene::Scene& scene) {
  if (scene.model == scene::ModelKind::kPulse) {
    return std::make_unique<PulseLegController>(scene.pulse);
  }
  return std::make_unique<ImpulseLegController>();
}

}  // namespace pronk::control
