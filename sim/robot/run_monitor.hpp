// The per-run record of a robot run: the body state the controller sees, the energy balance
// and its drift monitor, the sampled trajectory and the per-step contact monitors.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/control/body_state.hpp"
#include "sim/math/rotation.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/reduced/run_record.hpp"
#include "sim/robot/robot_events.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/robot/robot_system.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Vector3d;

/// Per-run bookkeeping shared by the step observer and the loop.
struct RunMonitor {
  RunMonitor(const scene::Scene& s, const RobotModel& m, const RobotSystem& y,
             const pr::MechanismSystem& ms, RobotRunResult& o)
      : scene(s), model(m), sys(y), msys(ms), out(o) {}
  const scene::Scene& scene;
  const RobotModel& model;
  const RobotSystem& sys;
  const pr::MechanismSystem& msys;
  RobotRunResult& out;
  bool record = true;
  double dissipated = 0.0, work = 0.0;
  double positive_work = 0.0;  ///< leg actuators' work, positive steps only [J]
  double balance0 = 0.0;       ///< energy balance at the start [J]
  /// The worst sampled departure of the balance [J] and where it first exceeded `blowup`.
  double sampled_drift = 0.0, blowup = 0.0, blowup_time = -1.0, blowup_drift = 0.0;
  bool stance = false;
  std::vector<bool> in_contact;
  std::vector<Eigen::Vector2d> contact_start;
  double stride_slip = 0.0;
  double contact_begin = 0.0;  ///< free stance hips: first foot landing of this stance [s]
  double contact_vz = 0.0;     ///< the CoM's vertical velocity then [m/s]

  control::BodyState body_state(const ode::Vec& y) const {
    const pr::BodyFrame& f = msys.frames(y)[model.body];
    const Com c = body_com(model, y);
    control::BodyState s;
    s.position = c.x;
    s.velocity = c.v;
    s.rotation = f.rotation;
    s.attitude = Eigen::Quaterniond(f.rotation).normalized();
    s.omega = f.rotation.transpose() * msys.body_omega(model.body, y);
    s.euler123 = math::matrix_to_euler(f.rotation, math::EulerSet::k123);
    return s;
  }

  /// The energy balance at a sample time t with the flows up to t: its departure from the
  /// start enters the drift monitor (and the blow-up check); with `record` the sample is kept.
  void sample(double t, const ode::Vec& y, double dissipated_t, double work_t) {
    const pr::Energies e = sys.energies(y);
    const double drift =
        std::abs(e.total() + dissipated_t - work_t - out.monitors.hip_work - balance0);
    sampled_drift = std::max(sampled_drift, std::isfinite(drift) ? drift : 1e300);
    if (blowup_time < 0.0 && !(drift <= blowup)) {
      blowup_time = t;
      blowup_drift = drift;
    }
    if (!record) return;
    const control::BodyState s = body_state(y);
    reduced::Sample smp;
    smp.t = t;
    smp.position = s.position;
    smp.velocity = s.velocity;
    smp.euler123 = s.euler123;
    smp.omega = s.omega;
    smp.setpoint = scene.controller.setpoint_position + scene.controller.setpoint_velocity * t;
    smp.stance = stance;
    RobotSample rs;
    rs.t = t;
    rs.energies = e;
    rs.dissipated = dissipated_t;
    rs.actuator_work = work_t + out.monitors.hip_work;
    rs.actuator_force = sys.actuator_forces(y);
    for (size_t i = 0; i < model.hip.size(); ++i) {
      // Σ actuator forces on the body (world), as the reduced models' leg force.
      smp.leg_force_world += rs.actuator_force[i] * sys.push_world(i, y);
    }
    if (model.spring_legs) {
      rs.normal_force = sys.normal_forces(y);
      for (size_t i = 0; i < model.foot.size(); ++i)
        rs.foot_z.push_back(sys.foot_position(i, y).z());
    }
    out.run.trajectory.push_back(smp);
    out.samples.push_back(std::move(rs));
  }

  /// Monitors at the end of an accepted step.
  void monitor(const ode::Vec& y) {
    const pr::StateMonitors m = msys.monitors(y);
    out.monitors.max_strain = std::max(out.monitors.max_strain, m.max_strain);
    out.monitors.max_penetration = std::max(out.monitors.max_penetration, m.max_penetration);
    if (!model.spring_legs) return;
    if (model.quasi_static_feet) {
      monitor_feet(y);
      return;
    }
    for (size_t i = 0; i < model.foot.size(); ++i) {
      const int f = model.foot[i];
      const Eigen::Vector2d xy = y.segment<2>(6 * f);
      if (y[6 * f + 2] < 0.0) {
        if (!in_contact[i]) contact_start[i] = xy;
        in_contact[i] = true;
        const double slip = (xy - contact_start[i]).norm();
        stride_slip = std::max(stride_slip, slip);
        out.monitors.max_slip = std::max(out.monitors.max_slip, slip);
        const pr::MechanismSystem::Contact c =
            msys.contact(model.ground, pr::NodeRef{pr::NodeRef::Kind::kMass, f}, y);
        if (c.normal > 0.0) {
          out.monitors.max_friction_ratio =
              std::max(out.monitors.max_friction_ratio, c.friction.norm() / c.normal);
        }
      } else {
        in_contact[i] = false;
      }
    }
  }
  /// monitor() of quasi-static feet: a landed foot's slip from where it landed and its
  /// friction ratio |F_t| / N.
  void monitor_feet(const ode::Vec& y) {
    std::vector<Vector3d> ft;
    std::vector<double> nf;
    for (size_t i = 0; i < model.foot.size(); ++i) {
      if (!sys.pinned(i)) {
        in_contact[i] = false;
        continue;
      }
      const Eigen::Vector2d xy = y.segment<2>(sys.foot_state(i));
      if (!in_contact[i]) contact_start[i] = xy;
      in_contact[i] = true;
      const double slip = (xy - contact_start[i]).norm();
      stride_slip = std::max(stride_slip, slip);
      out.monitors.max_slip = std::max(out.monitors.max_slip, slip);
      if (ft.empty()) {
        ft = sys.friction_forces(y);
        nf = sys.normal_forces(y);
      }
      if (nf[i] > 0.0) {
        out.monitors.max_friction_ratio =
            std::max(out.monitors.max_friction_ratio, ft[i].norm() / nf[i]);
      }
    }
  }
};

// Energy put in (or taken out) by placing the legs [J].
inline void book_hip_work(RobotMonitors& m, double dE) {
  m.hip_work += dE;
  m.positive_hip_work += std::max(0.0, dE);
}
}  // namespace pronk::robot::detail
