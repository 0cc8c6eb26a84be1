// The robot run's control layers: the reduced models' three layers planned as pulses, one set
// per hop-height setpoint, and the spring legs' layer that removes the elastic rebound.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "sim/control/body_controller.hpp"
#include "sim/control/leg_controller.hpp"
#include "sim/control/stance_planner.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/robot/run_data.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::robot::detail {

using Eigen::Vector3d;

/// The spring-leg leg layer (Ridgely 2001, §2.8.1): the springs return the touchdown
/// momentum, so the actuators are asked for the body controller's request minus
/// the elastic rebound -2 m v_z. Wraps the unchanged body controller.
class SpringReboundController final : public control::BodyController {
 public:
  /// push: the legs' common push direction, body frame (prismatic legs push only
  /// along it, so the linear request is projected on it before allocation).
  /// hips: mean hip position, body frame [m]; gravity [m/s^2]; stance: expected
  /// stance duration [s] (0: the springs' moment is not compensated).
  /// trim: extra vertical takeoff speed asked of the legs (hop-height feedback) [m/s].
  SpringReboundController(const control::BodyController& inner, double mass, const Vector3d* push,
                          const Vector3d& hips, double gravity, const double* stance,
                          const double* trim)
      : inner_(inner),
        mass_(mass),
        push_(push),
        hips_(hips),
        gravity_(gravity),
        stance_(stance),
        trim_(trim) {}
  control::BodyCommand command(double t, const control::BodyState& s) const override {
    control::BodyCommand c = inner_.command(t, s);
    const double rebound = -2.0 * mass_ * std::min(0.0, s.velocity.z());  // [N s]
    c.P_world.z() += mass_ * *trim_ - rebound;
    const Vector3d d = s.rotation * *push_;
    c.P_world = c.P_world.dot(d) * d;
    // The springs' impulse (rebound plus the weight over the stance) acts along the
    // legs at the hips, off the CoM when the legs lean: its moment is the actuators'
    // to cancel, or it pitches the body (legs at the hips below the CoM).
    if (d.z() > 0.1) {
      const Vector3d P_springs = (rebound + mass_ * gravity_ * *stance_) / d.z() * d;
      c.H_body -= hips_.cross(s.rotation.transpose() * P_springs);
    }
    return c;
  }

 private:
  const control::BodyController& inner_;
  double mass_;
  const Vector3d* push_;
  Vector3d hips_;
  double gravity_;
  const double* stance_;
  const double* trim_;
};

/// The same three control layers as the reduced models, planned as constant-force pulses
/// (the pulse settings), one set per hop-height setpoint (controller.hop_height_changes);
/// the spring legs' layer removes the rebound.
class ControlLayers {
 public:
  ControlLayers(const scene::Scene& scene, const RobotModel& model, const RunData& data)
      : spring_legs_(model.spring_legs) {
    scene::Scene plan_scene = scene;
    plan_scene.model = scene::ModelKind::kPulse;
    if (model.spring_legs) plan_scene.pulse.gravity_compensation = false;
    Vector3d mean_hip = Vector3d::Zero();  // body frame [m]
    for (const Vector3d& h : model.hip) mean_hip += h / static_cast<double>(model.hip.size());
    auto add_layer = [&](double from, double hop_height) {
      Layer L;
      L.scene = std::make_unique<scene::Scene>(plan_scene);
      L.scene->controller.hop_height = hop_height;
      L.pd = std::make_unique<control::PdBodyController>(
          L.scene->controller, scene.gravity, scene.legs.length, !scene.legs.body_only, false,
          L.scene->pulse.mode == scene::PulseMode::kDuration ? L.scene->pulse.duration : 0.0);
      L.rebound = std::make_unique<SpringReboundController>(
          *L.pd, scene.body.mass, &data.common_push, mean_hip, scene.gravity, &data.spring_stance,
          &data.hop_trim);
      L.legs = control::make_leg_controller(*L.scene);
      L.from = from;
      layers_.push_back(std::move(L));
    };
    add_layer(0.0, scene.controller.hop_height);
    for (const auto& [time, h] : scene.controller.hop_height_changes) add_layer(time, h);
  }
  /// The hop height asked at time t [m].
  double hop_height(double time) const { return at(time).scene->controller.hop_height; }
  /// The stance context at time t: with the spring legs' rebound layer, or the total
  /// request (leg placement).
  control::StanceContext context(double time, bool total) const {
    const Layer& L = at(time);
    const control::BodyController& b =
        spring_legs_ && !total ? static_cast<const control::BodyController&>(*L.rebound) : *L.pd;
    return control::StanceContext{*L.scene, b, *L.legs};
  }

 private:
  struct Layer {
    std::unique_ptr<scene::Scene> scene;
    std::unique_ptr<control::PdBodyController> pd;
    std::unique_ptr<SpringReboundController> rebound;
    std::unique_ptr<control::LegController> legs;
    double from = 0.0;  ///< in use from this time on [s]
  };
  const Layer& at(double time) const {
    size_t k = 0;
    while (k + 1 < layers_.size() && layers_[k + 1].from <= time) ++k;
    return layers_[k];
  }
  bool spring_legs_;
  std::vector<Layer> layers_;
};

}  // namespace pronk::robot::detail
