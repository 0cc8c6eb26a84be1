// Runs the three control layers at a touchdown: body controller -> impulse
// allocation -> leg controllers, with the pulse model's gravity compensation
// (Ridgely 2001, §2.6.1). Shared by every model.
#pragma once

#include <string>
#include <vector>

#include "sim/control/allocation.hpp"
#include "sim/control/body_controller.hpp"
#include "sim/control/leg_controller.hpp"

namespace pronk::control {

struct StancePlan {
  BodyCommand command;  ///< what the body controller asked for
  Eigen::Vector3d P_body =
      Eigen::Vector3d::Zero();  ///< net linear impulse handed to the legs, body [N s]
  Eigen::Vector3d H_body =
      Eigen::Vector3d::Zero();        ///< net angular impulse handed to the legs, body [N m s]
  double gravity_compensation = 0.0;  ///< m g T added to the vertical impulse [N s]
  double duration = 0.0;              ///< stance duration T [s]; 0 = instantaneous
  std::vector<Eigen::Vector3d> leg_impulse;                   ///< per leg, body frame [N s]
  std::vector<Eigen::Vector3d> leg_force;                     ///< per leg, body frame [N] (pulse)
  Eigen::Vector3d net_force_body = Eigen::Vector3d::Zero();   ///< Σ leg forces [N]
  Eigen::Vector3d net_moment_body = Eigen::Vector3d::Zero();  ///< Σ r_i × F_i [N m]
  AllocationStatus allocation_status = AllocationStatus::kOk;
  std::string allocation_message;
  int active_legs = 0;
};

struct StanceContext {
  const scene::Scene& scene;
  const BodyController& body;
  const LegController& legs;
};

/// Plans the stance starting at touchdown number `stride` (0-based) at time t [s].
StancePlan plan_stance(const StanceContext& ctx, long stride, double t, const BodyState& s);

/// Which legs push at stride number `stride` (gait and disabled legs).
std::vector<LegSlot> active_legs(const scene::Scene& scene, long stride);

}  // namespace pronk::control
