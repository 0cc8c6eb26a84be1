// Leg placement in flight: the leg directions for the predicted touchdown, and RobotRun's hip
// placement at the apex (legs turned in the air, level feet).

#include "sim/robot/leg_placement.hpp"

#include <algorithm>
#include <cmath>

#include "sim/robot/robot_run.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

/// Leg placement for the predicted touchdown: every leg parallel to the net linear
/// impulse the legs must deliver (body frame, no body-y part), within max_angle of
/// -z, so the spring rebound pushes where the impulse must go without adding a
/// moment of its own; the moments are left to the actuators. Unit directions hip -> foot.
std::vector<Vector3d> leg_directions(const control::StancePlan& plan, size_t legs,
                                     double max_angle) {
  std::vector<Vector3d> u(legs, -Vector3d::UnitZ());
  const Vector3d p = plan.P_body;
  if (!(p.z() > 1e-12)) return u;  // no upward push: legs straight down
  const double angle = std::clamp(std::atan2(p.x(), p.z()), -max_angle, max_angle);
  for (auto& ui : u) ui = Vector3d(-std::sin(angle), 0.0, -std::cos(angle));
  return u;
}

namespace {

/// The unit leg (hip -> foot) for the foot at horizontal offset r from the hip [m]: with the
/// stance roll held, its part across the body (the hips' ab/adduction plane, turned by the
/// heading from the world's x axis [rad]) along the takeoff velocity instead (see
/// free_leg_direction); within max_angle of the vertical.
Vector3d leg_for_foot(Eigen::Vector2d r, double leg, double max_angle, bool held_roll,
                      const Vector3d& v_takeoff, double heading) {
  if (held_roll && v_takeoff.z() > 1e-12) {
    const Eigen::Rotation2Dd to_world(heading);
    Eigen::Vector2d r_body = to_world.inverse() * r;
    const double v_across = (to_world.inverse() * v_takeoff.head<2>()).y();
    r_body.y() = -leg * v_across / std::hypot(v_across, v_takeoff.z());
    r = to_world * r_body;
  }
  const double r_max = leg * std::sin(max_angle);
  if (r.norm() > r_max) r *= r_max / r.norm();
  return Vector3d(r.x(), r.y(), -std::sqrt(std::max(0.0, leg * leg - r.squaredNorm()))) / leg;
}

}  // namespace

/// Leg placement for free stance hips (world frame, unit hip -> foot): the leg,
/// a strut from hip to foot during the stance, pushes along its mean direction,
/// so the foot is put where the mean foot -> hip line over the stance is parallel
/// to the net impulse the ground must give, P = P_legs + m g T_s (world [N s]):
/// half the stance's horizontal travel ahead of that, v T_s / 2 (Raibert's
/// neutral point, corrected by the impulse's tilt). v: horizontal CoM velocity
/// at touchdown [m/s]; stance: expected stance duration T_s [s]; leg: leg length
/// [m]; max_angle: limit from the vertical [rad].
/// held_roll: with the stance roll held (stance attitude feedback) the body moves
/// over its gripped feet only along the legs in the lateral plane (ab/adduction is
/// held too), so the lateral velocity across the legs is lost at touchdown and the
/// takeoff velocity follows the legs: the leg is put along the desired takeoff
/// velocity v_takeoff in y instead (no neutral point).
Vector3d free_leg_direction(const Vector3d& P, const Vector3d& v, double stance, double leg,
                            double max_angle, bool held_roll, const Vector3d& v_takeoff,
                            double heading) {
  Eigen::Vector2d r = 0.5 * stance * v.head<2>();
  if (P.z() > 1e-12) r -= leg * P.head<2>() / P.norm();
  return leg_for_foot(r, leg, max_angle, held_roll, v_takeoff, heading);
}

/// The inverted-pendulum placement (see the header).
Vector3d pendulum_leg_direction(const Vector3d& P, const Vector3d& v0, double stance, double leg,
                                double mass, double max_angle, bool held_roll,
                                const Vector3d& v_takeoff, double heading) {
  Eigen::Vector2d r = 0.5 * stance * v0.head<2>();
  if (P.z() > 1e-12 && stance > 0.0 && mass > 0.0) {
    const double w = std::sqrt(P.z() / (stance * mass * leg));  // [1/s]
    const double wt = w * stance;
    r = ((std::cosh(wt) - 1.0) * v0.head<2>() - P.head<2>() / mass) / (w * std::sinh(wt));
  }
  return leg_for_foot(r, leg, max_angle, held_roll, v_takeoff, heading);
}

std::vector<Vector3d> yaw_leg_directions(const Vector3d& d,
                                         const std::vector<Eigen::Vector2d>& hips, double Hz,
                                         double Pz, double leg, double max_angle) {
  std::vector<Vector3d> u(hips.size(), d);
  if (hips.empty() || !(Pz > 1e-12) || !(d.z() < -1e-12) || Hz == 0.0) return u;
  const double n = static_cast<double>(hips.size());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& h : hips) centre += h / n;
  double levers = 0.0;  // sum of |lever|^2 [m^2]
  for (const auto& h : hips) levers += (h - centre).squaredNorm();
  if (!(levers > 1e-12)) return u;
  for (size_t i = 0; i < hips.size(); ++i) {
    const Eigen::Vector2d lever = hips[i] - centre;
    const Eigen::Vector2d p = Hz * Eigen::Vector2d(-lever.y(), lever.x()) / levers;  // [N s]
    u[i] = leg_for_foot(leg * d.head<2>() - leg * n * p / Pz, leg, max_angle, false, d, 0.0);
  }
  return u;
}

double free_leg_response(const Vector3d& P, double stance, double leg, double mass) {
  return std::clamp(1.0 - stance * P.norm() / (4.0 * mass * leg), 0.1, 1.0);
}

/// Hip placement (hip_rotation): plan the stance at the predicted (ballistic) touchdown and
/// turn each leg in the air along its total impulse; the foot moves with the leg (its
/// energy change is hip work).
void RobotRun::place_legs(double t, ode::Vec& y) {
  control::BodyState s = trimmed(sensed(run_.body_state(y)));
  if (!(s.position.z() - l_ > 0.0)) return;
  Matrix3d R_td;
  const std::vector<Vector3d> u = placement(t, y, s, R_td);
  const std::vector<double> rest = level_rest_lengths(s, R_td, u);
  const double e_before = sys_.energies(y).total();
  const pr::BodyFrame f = msys_.frames(y)[model_.body];
  const Vector3d w = msys_.body_omega(model_.body, y);
  for (size_t i = 0; i < legs_; ++i) {
    if (sys_.free(i)) continue;       // still on the ground
    if (sys_.quasi_static()) {        // a massless foot: turned and set to its new rest length
      sys_.foot_rest()[i] = rest[i];  // (its shortening, its spring's deflection, kept)
      sys_.foot_direction()[i] = u[i];
      data_.push[i] = -u[i];
      continue;
    }
    const int foot = model_.foot[i];
    const double m = model_.mechanism.masses[foot].mass;
    const pr::NodeRef ghost{pr::NodeRef::Kind::kGhost,
                            model_.mechanism.surfaces[model_.slide[i]].ghost};
    const Vector3d hip = msys_.node_position(ghost, y);
    const Vector3d d_old = f.rotation * (-data_.push[i]);
    const Vector3d d_new = f.rotation * u[i];
    const Vector3d xf = y.segment<3>(6 * foot);
    // (the spring keeps its deflection when its rest length changes)
    double& rest_now = data_.inputs.rest_length[static_cast<size_t>(model_.leg_spring[i])];
    const double ext = (xf - hip).dot(d_old) + rest[i] - rest_now;
    rest_now = rest[i];
    const Vector3d vrel = y.segment<3>(6 * foot + 3) / m - (f.com_velocity + w.cross(xf - f.com));
    const Vector3d xn = hip + ext * d_new;
    const Vector3d vn = f.com_velocity + w.cross(xn - f.com) + vrel.dot(d_old) * d_new;
    y.segment<3>(6 * foot) = xn;
    y.segment<3>(6 * foot + 3) = m * vn;
    data_.inputs.surfaces[model_.slide[i]].direction = u[i];
    data_.push[i] = -u[i];
  }
  data_.common_push = -u[0];  // (a leg still on the ground keeps its direction)
  book_work(e_before, y);
}

/// The legs' directions (body frame, unit hip -> foot) for the stance planned at the
/// predicted ballistic touchdown; s becomes the predicted touchdown state, R_td the body
/// attitude then (after the flight at constant angular velocity).
std::vector<Vector3d> RobotRun::placement(double t, const ode::Vec& y, control::BodyState& s,
                                          Matrix3d& R_td) {
  const double tf = std::sqrt(2.0 * (s.position.z() - l_) / g_);
  const Vector3d w_world = msys_.body_omega(model_.body, y);
  R_td = msys_.frames(y)[model_.body].rotation;
  if (w_world.norm() * tf > 1e-12) {
    R_td = Eigen::AngleAxisd(w_world.norm() * tf, w_world.normalized()) * R_td;
  }
  s.position += s.velocity * tf + Vector3d(0, 0, -0.5 * g_ * tf * tf);
  s.velocity.z() -= g_ * tf;
  const control::StancePlan pred =
      control::plan_stance(control_.context(t + tf, true), touchdowns_, t + tf, s);
  if (!free_stance_) return leg_directions(pred, legs_, prs_.max_leg_angle);
  // The legs' total push plus the weight carried over the stance, placed in
  // the world and turned into the body frame the body will have at touchdown.
  Vector3d P = pred.command.P_world;
  P.z() += total_mass_ * g_ * data_.spring_stance;
  data_.placed = P.head<2>();
  data_.has_placed = true;
  data_.placed_response =
      free_leg_response(P, data_.spring_stance, model_.rest_length[0], total_mass_);
  P.head<2>() += data_.placement_trim;
  // The hips' mean speed over the stance: the CoM's plus half the change asked.
  const Vector3d v_mean = s.velocity + 0.5 * pred.command.P_world / total_mass_;
  const bool held_roll = prs_.stance_kp[0] > 0.0 || prs_.stance_kd[0] > 0.0;
  // Desired takeoff velocity: lateral as the controller asks, vertical as the
  // springs return it (the touchdown speed).
  Vector3d v_takeoff = s.velocity + pred.command.P_world / total_mass_;
  v_takeoff.head<2>() += data_.placement_trim / total_mass_;
  v_takeoff.z() = std::max(-s.velocity.z(), 0.1);
  // The pendulum rule holds the roll across the body as it is headed at touchdown and turns
  // the legs apart for the yaw asked; the neutral-point rule (the older placement, kept as it
  // was for the designs tuned with it) holds it across the world's x axis, legs parallel.
  const double heading = prs_.pendulum_placement ? std::atan2(R_td(1, 0), R_td(0, 0)) : 0.0;
  const Vector3d d =
      prs_.pendulum_placement
          ? pendulum_leg_direction(P, s.velocity, data_.spring_stance, model_.rest_length[0],
                                   total_mass_, prs_.max_leg_angle, held_roll, v_takeoff, heading)
          : free_leg_direction(P, v_mean, data_.spring_stance, model_.rest_length[0],
                               prs_.max_leg_angle, held_roll, v_takeoff, heading);
  std::vector<Vector3d> u(legs_, d);
  if (prs_.pendulum_placement) {
    std::vector<Eigen::Vector2d> hips(legs_);
    for (size_t i = 0; i < legs_; ++i) hips[i] = (R_td * model_.hip[i]).head<2>();
    u = yaw_leg_directions(d, hips, (R_td * pred.command.H_body).z(), P.z(), model_.rest_length[0],
                           prs_.max_leg_angle);
  }
  for (auto& ui : u) ui = R_td.transpose() * ui;
  return u;
}

/// Level feet: each leg's rest length such that every foot reaches the ground together at
/// the predicted touchdown attitude R_td (CoM at s.position); the current ones otherwise.
std::vector<double> RobotRun::level_rest_lengths(const control::BodyState& s, const Matrix3d& R_td,
                                                 const std::vector<Vector3d>& u) const {
  std::vector<double> rest(legs_);
  for (size_t i = 0; i < legs_; ++i) {
    rest[i] = sys_.quasi_static()
                  ? sys_.foot_rest()[i]
                  : data_.inputs.rest_length[static_cast<size_t>(model_.leg_spring[i])];
  }
  if (!(prs_.level_feet && free_stance_)) return rest;
  double z_mean = 0.0;
  std::vector<double> hz(legs_), dz_leg(legs_);
  for (size_t i = 0; i < legs_; ++i) {
    hz[i] = s.position.z() + (R_td * model_.hip[i]).z();
    dz_leg[i] = (R_td * u[i]).z();
    z_mean += (hz[i] + model_.rest_length[i] * dz_leg[i]) / static_cast<double>(legs_);
  }
  for (size_t i = 0; i < legs_; ++i) {
    if (sys_.free(i) || !(dz_leg[i] < -0.1)) continue;
    rest[i] = std::clamp((z_mean - hz[i]) / dz_leg[i], 0.75 * model_.rest_length[i],
                         1.25 * model_.rest_length[i]);
  }
  return rest;
}

}  // namespace pronk::robot::detail
