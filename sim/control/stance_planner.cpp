#include "sim/control/stance_planner.hpp"

#include <algorithm>
#include <cmath>

namespace pronk::control {

using Eigen::Vector3d;

std::vector<LegSlot> active_legs(const scene::Scene& scene, long stride) {
  const auto& legs = scene.legs;
  std::vector<LegSlot> slots(legs.hips.size());
  for (size_t i = 0; i < legs.hips.size(); ++i) {
    slots[i].hip_body = legs.hips[i];
    slots[i].active = !legs.disabled[i];
  }
  if (scene.controller.gait == scene::Gait::kAlternate && !scene.controller.gait_groups.empty()) {
    const auto& group =
        scene.controller
            .gait_groups[static_cast<size_t>(stride) % scene.controller.gait_groups.size()];
    for (size_t i = 0; i < slots.size(); ++i) {
      if (std::find(group.begin(), group.end(), static_cast<int>(i)) == group.end()) {
        slots[i].active = false;
      }
    }
  }
  return slots;
}

namespace {

// Allocates the body-frame request and fills the plan's leg impulses.
void allocate_into(const scene::Scene& scene, const std::vector<LegSlot>& slots, StancePlan& plan) {
  if (scene.legs.body_only) {
    // One virtual leg at the CoM that pushes any P and H.
    plan.leg_impulse.assign(1, plan.P_body);
    plan.allocation_status = AllocationStatus::kOk;
    plan.active_legs = 1;
    return;
  }
  AllocationResult r = allocate(slots, plan.P_body, plan.H_body, scene.controller.allocation);
  plan.leg_impulse = std::move(r.leg_impulse);
  plan.allocation_status = r.status;
  plan.allocation_message = std::move(r.message);
  plan.active_legs = static_cast<int>(
      std::count_if(slots.begin(), slots.end(), [](const LegSlot& l) { return l.active; }));
}

}  // namespace

StancePlan plan_stance(const StanceContext& ctx, long stride, double t, const BodyState& s) {
  const scene::Scene& scene = ctx.scene;
  StancePlan plan;
  plan.command = ctx.body.command(t, s);
  const std::vector<LegSlot> slots =
      scene.legs.body_only ? std::vector<LegSlot>{} : active_legs(scene, stride);
  const double mg = scene.body.mass * scene.gravity;
  const bool compensate =
      scene.model == scene::ModelKind::kPulse && scene.pulse.gravity_compensation;

  // The stance duration may depend on the allocation (max_force mode) and the
  // compensation on the duration: iterate the fixed point T = T(alloc(P + m g T e_z)).
  // It contracts with factor ~ m g / F_max per iteration.
  double T = 0.0;
  for (int iter = 0; iter < 50; ++iter) {
    Vector3d P = plan.command.P_world;
    P.z() += compensate ? mg * T : 0.0;
    plan.P_body = s.rotation.transpose() * P;
    // Telescoping legs cannot push along body y: banking handles lateral motion.
    if (!scene.legs.body_only) plan.P_body.y() = 0.0;
    plan.H_body = plan.command.H_body;
    allocate_into(scene, slots, plan);
    const double T_new = ctx.legs.stance_duration(plan.leg_impulse);
    const bool converged = std::abs(T_new - T) <= 1e-14 + 1e-13 * T_new;
    T = T_new;
    if (!compensate || converged) break;
  }
  plan.gravity_compensation = compensate ? mg * T : 0.0;
  plan.duration = T;

  plan.net_force_body.setZero();
  plan.net_moment_body.setZero();
  plan.leg_force.assign(plan.leg_impulse.size(), Vector3d::Zero());
  if (T > 0.0) {
    for (size_t i = 0; i < plan.leg_impulse.size(); ++i) {
      plan.leg_force[i] = ctx.legs.force(plan.leg_impulse[i], T);
      plan.net_force_body += plan.leg_force[i];
      if (!scene.legs.body_only)
        plan.net_moment_body += scene.legs.hips[i].cross(plan.leg_force[i]);
    }
    if (scene.legs.body_only) plan.net_moment_body = plan.H_body / T;
  }
  return plan;
}

}  // namespace pronk::control
