// RobotRun's leg actuation: the leg controllers' constant-force pulses at touchdown, the
// spring legs' armed actuators firing at the bottom of the stance, and the energy thrust.

#include "sim/robot/robot_run.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/robot/thrust_law.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

/// Leg controllers: a constant force along each leg for the stance duration T; with a
/// force limit the pulse saturates, and with impulse feedback the actuator stays on until
/// its delivered impulse reaches the allocation (Ridgely 2001, §5.4). Sets the legs' forces and
/// switch-off times and the stride's peak force and angular impulse; returns the stance's
/// end [s].
double RobotRun::command_actuators(const control::StancePlan& plan, double t) {
  const double T = prs_.actuators ? plan.duration : 0.0;
  double stance_end = t;
  Vector3d H = Vector3d::Zero();
  double peak = 0.0;
  std::fill(data_.leg_force.begin(), data_.leg_force.end(), 0.0);
  std::fill(data_.armed_force.begin(), data_.armed_force.end(), 0.0);
  for (size_t i = 0; i < legs_ && T > 0.0 && i < plan.leg_impulse.size(); ++i) {
    const Vector3d p = plan.leg_impulse[i];
    double impulse = 0.0;  // signed along the push direction [N s]
    if (model_.spring_legs) {
      impulse = p.dot(data_.push[i]);
    } else if (p.norm() > 0.0) {
      data_.push[i] = p.normalized();
      impulse = p.norm();
    }
    if (impulse == 0.0) continue;
    double f = impulse / T, duration = T;
    if (belief_.pseudo_rigid.actuator_max_force > 0.0 &&
        std::abs(f) > belief_.pseudo_rigid.actuator_max_force) {
      f = std::copysign(belief_.pseudo_rigid.actuator_max_force, f);
      if (prs_.impulse_feedback) {
        // The leg measures the net impulse it gives the body (its force minus its
        // share s of the weight it was compensating for, shares in proportion to
        // the legs' impulses) and stays on until that reaches its allocation net of
        // compensation: F_max T' - s T' = p - s T.
        double sum = 0.0;
        for (const auto& q : plan.leg_impulse) sum += q.norm();
        const double share =
            sum > 0.0 ? plan.gravity_compensation / T * std::abs(impulse) / sum : 0.0;
        const double net_rate = belief_.pseudo_rigid.actuator_max_force - share;
        duration = net_rate > 0.0 ? (std::abs(impulse) - share * T) / net_rate
                                  : std::abs(impulse) / belief_.pseudo_rigid.actuator_max_force;
      }
      ++result.run.warnings["actuator_saturated"];
    }
    data_.leg_force[i] = f;
    data_.off_time[i] = t + duration;
    data_.armed_force[i] = f;
    data_.armed_duration[i] = duration;
    stance_end = std::max(stance_end, data_.off_time[i]);
    peak = std::max(peak, std::abs(f));
    H += model_.hip[i].cross(f * duration * data_.push[i]);
  }
  current_.peak_leg_force = peak;
  current_.H_delivered = H;
  return stance_end;
}

/// The bottom of a spring stance: the armed actuators fire.
void RobotRun::on_bottom(double t, const ode::Vec& y) {
  data_.armed = false;
  double stance_end = t;
  if (prs_.thrust == scene::PseudoRigid::Thrust::kEnergy) {
    stance_end = energy_thrust(t, y);
  } else {
    for (size_t i = 0; i < legs_; ++i) {
      data_.leg_force[i] = data_.armed_force[i];
      data_.off_time[i] = t + data_.armed_duration[i];
      if (data_.leg_force[i] != 0.0) stance_end = std::max(stance_end, data_.off_time[i]);
    }
  }
  if (have_stride_) current_.stance_duration = stance_end - current_.t_touchdown;
  set_actuators();
}

/// The energy thrust (PseudoRigid::Thrust::kEnergy) at the bottom of the stance. The grounded
/// legs' springs and dampers lumped vertically give the collective vertical force that reaches
/// the target apex (thrust_law.hpp), held to the predicted lift-off. It is shared among the
/// grounded legs (share_thrust) so that their total moment about the CoM (roll, pitch) is the
/// planned one: the plan's differential impulses spread over the same time; the collective
/// itself, on legs that lean, adds none. Returns the stance's end [s].
double RobotRun::energy_thrust(double t, const ode::Vec& y) {
  const Vector3d com = body_com(model_, y).x;
  std::fill(data_.leg_force.begin(), data_.leg_force.end(), 0.0);
  std::vector<size_t> on;
  std::vector<Vector3d> u, arm;
  double K = 0.0, C = 0.0, s_v = 0.0, f_mean = 0.0;
  for (size_t i = 0; i < legs_; ++i) {
    if (data_.armed_force[i] == 0.0 || (model_.leg_spring[i] < 0 && !sys_.quasi_static())) {
      continue;
    }
    const Vector3d foot = sys_.foot_position(i, y);
    const Vector3d hip = msys_.node_position(model_.hip_node[i], y);
    const Vector3d leg = hip - foot;
    if (foot.z() > kFootLift || !(leg.z() > 0.1 * leg.norm())) continue;  // not pushing up
    const double dz = leg.z() / leg.norm();
    const double rest = sys_.quasi_static()
                            ? sys_.foot_rest()[i]
                            : data_.inputs.rest_length[static_cast<size_t>(model_.leg_spring[i])];
    K += belief_.pseudo_rigid.leg_stiffness * dz * dz;
    C += belief_.pseudo_rigid.leg_damping * dz * dz;
    s_v += (rest - leg.norm()) * dz;
    f_mean += data_.armed_force[i];
    on.push_back(i);
    u.push_back(leg.normalized());
    arm.push_back(hip - com);
  }
  const size_t n = on.size();
  if (n == 0) return t;
  f_mean /= static_cast<double>(n);
  ThrustModel m;
  m.mass = belief_.body.mass;
  m.gravity = g_;
  m.stiffness = K;
  m.damping = C;
  m.z_bottom = com.z();
  m.z_rest = com.z() + s_v / static_cast<double>(n);
  double dz_sum = 0.0;
  for (const Vector3d& d : u) dz_sum += d.z();
  const double f_max = belief_.pseudo_rigid.actuator_max_force > 0.0
                           ? belief_.pseudo_rigid.actuator_max_force * dz_sum
                           : 20.0 * m.mass * g_;
  const double apex = l_ + control_.hop_height(t) + data_.apex_trim;
  const ThrustPlan plan = plan_thrust(m, apex, -0.5 * K * (m.z_rest - m.z_bottom), f_max);
  if (plan.saturated) ++result.run.warnings["thrust_saturated"];
  const double T = std::max(plan.duration, 1e-6);
  std::vector<double> planned(n);
  for (size_t k = 0; k < n; ++k) {
    planned[k] = (data_.armed_force[on[k]] - f_mean) * data_.armed_duration[on[k]] / T;
  }
  const std::vector<double> f = share_thrust(plan.force, u, arm, planned);
  for (size_t k = 0; k < n; ++k) {
    data_.leg_force[on[k]] = f[k];
    data_.off_time[on[k]] = t + T;
  }
  data_.stride_force = data_.leg_force;
  current_.peak_leg_force = 0.0;
  for (double fi : data_.leg_force) {
    current_.peak_leg_force = std::max(current_.peak_leg_force, std::abs(fi));
  }
  return t + T;
}

}  // namespace pronk::robot::detail
