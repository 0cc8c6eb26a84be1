#include "sim/scene/robot_scaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pronk::scene {

Vec6 gain_scale(const Body& body) {
  const Vec3 I = body.inertia.diagonal();
  Vec6 s;
  s << body.mass, body.mass, body.mass, I.x(), I.y(), I.z();
  return s;
}

namespace {

// Working legs that push in one stride: every leg not disabled (a pronk), the smallest
// group of an alternating gait; 1 for the body-only robot's virtual leg.
int legs_per_stride(const Scene& s) {
  if (s.legs.body_only) return 1;
  auto working = [&](const std::vector<int>& group) {
    int n = 0;
    for (int i : group) n += s.legs.disabled[static_cast<size_t>(i)] ? 0 : 1;
    return n;
  };
  if (s.controller.gait == Gait::kAlternate && !s.controller.gait_groups.empty()) {
    int n = std::numeric_limits<int>::max();
    for (const auto& g : s.controller.gait_groups) n = std::min(n, working(g));
    return std::max(n, 1);
  }
  int n = 0;
  for (bool d : s.legs.disabled) n += d ? 0 : 1;
  return std::max(n, 1);
}

}  // namespace

double design_stance_time(const Scene& s) {
  if (s.pulse.mode == PulseMode::kDuration) return s.pulse.duration;
  const double m = s.body.mass, g = s.gravity;
  const double v = std::sqrt(2.0 * g * s.controller.hop_height);
  const double push = legs_per_stride(s) * s.pulse.max_force;
  const double net = s.pulse.gravity_compensation ? push - m * g : push;
  // Legs too weak to carry the body through a stance: no stance length fits; the longest
  // one a stride could have (half the flight) stands in.
  if (!(net > 0.0) || 2.0 * m * v / net > v / g) return v / g;
  return 2.0 * m * v / net;
}

StrideTiming design_stride(const Scene& s) {
  StrideTiming t;
  t.stance = s.model == ModelKind::kImpulse ? 0.0 : design_stance_time(s);
  const bool pulse_aware = s.controller.pulse_aware_hop && s.pulse.mode == PulseMode::kDuration;
  t.flight = hop_flight_time(s.gravity, s.controller.hop_height, t.stance, pulse_aware);
  return t;
}

double max_natural_frequency(double zeta, double period) {
  if (zeta >= 1.0) return std::numeric_limits<double>::infinity();
  return M_PI / (period * std::sqrt(1.0 - zeta * zeta));
}

void absolute_gains(const RelativeGains& g, const Scene& s, Vec6* kp, Vec6* kd) {
  Vec6 p = g.kp, d = g.kd;
  if (g.form == RelativeGains::Form::kResponse) {
    const StrideTiming t = design_stride(s);
    p.setZero();
    d.setZero();
    d[2] = 1.0;  // the hop-height law: Kd_z = m
    for (int c = 0; c < 5; ++c) {
      const auto z = response_poles(g.natural_frequency[c], g.damping_ratio[c], t.period());
      pd_channel_gains(z[0], z[1], t, &p[kResponseAxis[c]], &d[kResponseAxis[c]]);
    }
  }
  const Vec6 scale = gain_scale(s.body);
  *kp = p.cwiseProduct(scale);
  *kd = d.cwiseProduct(scale);
}

LateralLoop default_lateral_loop(const Scene& s) {
  return place_lateral_poles(kLateralPoles, design_stride(s), s.gravity);
}

double leg_stiffness_for_stance(const Scene& s, double stance_time) {
  const double n = s.legs.body_only ? 1.0 : static_cast<double>(s.legs.hips.size());
  return s.body.mass * M_PI * M_PI / (n * stance_time * stance_time);
}

double stance_for_duty(double duty, double flight) { return duty * flight / (1.0 - duty); }

double default_pulse_duration(const Scene& s) {
  return stance_for_duty(kDefaultDuty,
                         hop_flight_time(s.gravity, s.controller.hop_height, 0.0, false));
}

double default_leg_damping(const Scene& s) {
  const double n = static_cast<double>(std::max<size_t>(s.legs.hips.size(), 1));
  return kDefaultLegDampingRatio * 2.0 * std::sqrt(s.pseudo_rigid.leg_stiffness * s.body.mass / n);
}

PositionLoop default_position_loop(const Scene& s) {
  return place_position_poles(kPositionPoles, design_stride(s));
}

Eigen::Vector2d default_stance_kp_per_inertia(const Scene& s) {
  Eigen::Vector2d kp(kStanceKpPerInertia[0], kStanceKpPerInertia[1]);
  const Vec3& v = s.controller.setpoint_velocity;
  const double speed = std::hypot(v.x(), v.y());
  if (speed > 0.0) kp[0] = std::max(kp[0], kp[1] * std::abs(v.y()) / speed);
  return kp;
}

double default_stance_max_moment(const Scene& s) {
  double r = 0.0;
  for (const Vec3& h : s.legs.hips) r = std::max(r, std::hypot(h.x(), h.y()));
  return s.body.mass * s.gravity * r;
}

double default_foot_mass(const Body& body) { return body.mass / 1500.0; }

double default_contact_damping(const PseudoRigid& p) {
  return 2.0 * std::sqrt(p.contact_stiffness * p.foot_mass);
}

}  // namespace pronk::scene
