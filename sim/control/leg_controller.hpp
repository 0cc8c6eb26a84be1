// The bottom layer of the control hierarchy: each leg controller delivers its
// allocated linear impulse. In the reduced models a leg either delivers it
// instantly (impulse model) or as a constant body-fixed force over the stance
// (pulse model, Ridgely 2001, §2.6).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "sim/scene/scene.hpp"

namespace pronk::control {

class LegController {
 public:
  virtual ~LegController() = default;
  /// Stance duration T [s] needed to deliver the per-leg impulses [N s]
  /// (0 = instantaneous impulse). Legs with zero impulse are idle.
  virtual double stance_duration(const std::vector<Eigen::Vector3d>& leg_impulses) const = 0;
  /// Force [N] (body frame) of a leg with allocated impulse p [N s] during a stance of
  /// duration T [s]: constant p / T for the pulse legs.
  Eigen::Vector3d force(const Eigen::Vector3d& p, double T) const { return p / T; }
};

/// Instantaneous impulse delivery (impulse model).
class ImpulseLegController final : public LegController {
 public:
  double stance_duration(const std::vector<Eigen::Vector3d>&) const override { return 0.0; }
};

/// Constant-force pulses: `max_force` mode T = max_i |p_i| / F_max (seed
/// Newton-Euler), `duration` mode T fixed (seed spring-mass controller).
class PulseLegController final : public LegController {
 public:
  explicit PulseLegController(const scene::Pulse& pulse) : pulse_(pulse) {}
  double stance_duration(const std::vector<Eigen::Vector3d>& leg_impulses) const override;

 private:
  scene::Pulse pulse_;
};

std::unique_ptr<LegController> make_leg_controller(const scene::Scene& scene);

}  // namespace pronk::control
