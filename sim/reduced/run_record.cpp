#include "sim/reduced/run_record.hpp"

#include <cmath>

#include "sim/run/count_text.hpp"
#include "sim/run/hybrid_run.hpp"

namespace pronk::reduced {

StrideRecord open_stride(long index, double t, const control::BodyState& s,
                         const control::StancePlan& plan, const scene::Scene& scene,
                         std::map<std::string, long>& warnings) {
  StrideRecord r;
  r.index = index;
  r.t_touchdown = t;
  r.position = s.position;
  r.velocity = s.velocity;
  r.euler123 = s.euler123;
  r.omega = s.omega;
  r.setpoint = scene.controller.setpoint_position + scene.controller.setpoint_velocity * t;
  r.P_requested = plan.command.P_world;
  r.H_requested = plan.command.H_body;
  r.gravity_compensation = plan.gravity_compensation;
  r.active_legs = plan.active_legs;
  r.allocation = plan.allocation_status;
  if (plan.allocation_status != control::AllocationStatus::kOk) {
    ++warnings[plan.allocation_status == control::AllocationStatus::kLimited
                   ? "allocation_limited"
                   : "allocation_infeasible"];
  }
  return r;
}

void close_stride(StrideRecord& current, double t_next) {
  if (t_next > current.t_touchdown) {
    current.stride_time = t_next - current.t_touchdown;
    current.duty_cycle = current.stance_duration / current.stride_time;
  }
}

std::string fell_low_reason(const scene::Scene& scene, double t) {
  return "CoM fell below " + run::fmt(scene.simulation.fall_min_height) +
         " m at t = " + run::fmt(t) + " s";
}

std::string tilted_reason(const scene::Scene& scene, double t) {
  return "body tilted past " + run::fmt(scene.simulation.fall_max_tilt * 180.0 / M_PI) +
         " deg at t = " + run::fmt(t) + " s";
}

void finish_run(RunResult& r, double t, const control::BodyState& s, long touchdowns,
                const scene::Scene& scene) {
  const auto& sim = scene.simulation;
  r.t_end = t;
  r.final_position = s.position;
  r.final_velocity = s.velocity;
  r.final_euler123 = s.euler123;
  r.final_omega = s.omega;
  r.final_attitude = s.attitude;
  if (r.status == RunStatus::kCompleted) {
    r.reason = touchdowns >= sim.max_strides && t < sim.duration
                   ? "reached " + run::count_text(sim.max_strides, "stride")
                   : "reached t = " + run::fmt(t) + " s";
  }
}

}  // namespace pronk::reduced
