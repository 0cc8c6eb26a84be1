// The robot run's event functions (touchdown and fall heights, apex, the bottom of a spring
// stance, feet landing and lifting off, tilt) and the body's CoM they read.
#pragma once

#include <cmath>

#include "sim/ode/ode_system.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/robot/robot_system.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Vector3d;

struct Com {
  Vector3d x, v;  ///< [m], [m/s]
};

/// CoM position and velocity of the body: its four main masses and its dummy masses.
inline Com body_com(const RobotModel& m, const ode::Vec& y) {
  Com c{Vector3d::Zero(), Vector3d::Zero()};
  double total = 0.0;
  for (size_t j = 0; j < m.mechanism.masses.size(); ++j) {
    const auto& ms = m.mechanism.masses[j];
    if (ms.body != m.body && ms.dummy_of != m.body) continue;
    c.x += ms.mass * y.segment<3>(6 * j);
    c.v += y.segment<3>(6 * j + 3);
    total += ms.mass;
  }
  c.x /= total;
  c.v /= total;
  return c;
}

class ComHeightEvent final : public ode::EventFunction {
 public:
  ComHeightEvent(const RobotModel& m, double level) : m_(m), level_(level) {}
  double value(double, const ode::Vec& y) const override { return body_com(m_, y).x.z() - level_; }

 private:
  const RobotModel& m_;
  double level_;
};

class ApexEvent final : public ode::EventFunction {
 public:
  explicit ApexEvent(const RobotModel& m) : m_(m) {}
  double value(double, const ode::Vec& y) const override { return body_com(m_, y).v.z(); }

 private:
  const RobotModel& m_;
};

/// Bottom of a spring stance: the CoM's vertical velocity rises through zero.
class BottomEvent final : public ode::EventFunction {
 public:
  explicit BottomEvent(const RobotModel& m) : m_(m) {}
  double value(double, const ode::Vec& y) const override { return body_com(m_, y).v.z(); }
  int direction() const override { return 1; }

 private:
  const RobotModel& m_;
};

/// A foot crossing the ground plane z = 0 falling while its hip is locked (the foot
/// lands: the hip is freed), or rising through kFootLift above it while the hip is
/// free (lift-off: locked again). The hysteresis keeps a foot grazing the ground
/// (z ~ 0, v_z ~ 0) from landing and lifting off at the same instant forever.
constexpr double kFootLift = 2e-4;  ///< [m]
class FootEvent final : public ode::EventFunction {
 public:
  FootEvent(const RobotSystem& sys, size_t leg, int foot) : sys_(sys), leg_(leg), foot_(foot) {}
  double value(double, const ode::Vec& y) const override {
    // A quasi-static foot lands falling through the ground and lifts off when the ground's
    // normal force on it falls through zero (RobotSystem::foot_event).
    // A lifted quasi-static foot's hip is locked, as a foot mass's, once it rises kFootLift.
    if (foot_ < 0) {
      if (lifting()) return sys_.foot_position(leg_, y).z() - kFootLift;
      return sys_.foot_event(leg_, y);
    }
    return y[6 * foot_ + 2] - (sys_.free(leg_) ? kFootLift : 0.0);
  }
  int direction() const override { return sys_.free(leg_) && (foot_ >= 0 || lifting()) ? 1 : -1; }

 private:
  /// A quasi-static foot in the air whose hip is still free.
  bool lifting() const { return foot_ < 0 && sys_.free(leg_) && !sys_.pinned(leg_); }
  const RobotSystem& sys_;
  size_t leg_;
  int foot_;
};

class TiltEvent final : public ode::EventFunction {
 public:
  TiltEvent(const RobotModel& m, const pr::MechanismSystem& sys, double max_tilt)
      : m_(m), sys_(sys), cos_max_(std::cos(max_tilt)) {}
  double value(double, const ode::Vec& y) const override {
    return sys_.frames(y)[m_.body].rotation(2, 2) - cos_max_;
  }

 private:
  const RobotModel& m_;
  const pr::MechanismSystem& sys_;
  double cos_max_;
};

}  // namespace pronk::robot::detail
