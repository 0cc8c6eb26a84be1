// MuJoCo as the stepper of the robot's hybrid run ("model": "mujoco"): the run loop, its events,
// the controller and the records are the full model's (sim/robot/robot_run.hpp); only the
// integration of one step is MuJoCo's mj_step on the robot's MJCF model (robot_mjcf.hpp). The
// state the run reads and writes is the pseudo-rigid robot's with the rigid body (the body's CoM
// mass, each foot's mass, the body's quaternion and angular momentum), mapped to MuJoCo's qpos
// and qvel and back exactly (leg_joints.hpp). Before every step the run's inputs become
// MuJoCo's: each leg actuator's force (the stance attitude feedback included) as its motor's
// control, the leg spring's rest length as the slide's spring reference, the hip placement as
// the hinge equalities' targets, a landed foot's free hip as its pitch equality switched off.
//
// Events land on MuJoCo's own trajectory: retake() redoes the step from its saved start to the
// event time. Dense output between steps is linear (MuJoCo has none). A step that raises any of
// MuJoCo's warnings (mjData.warning: bad qpos, qvel or qacc, which make MuJoCo reset its state,
// or a full contact or constraint list) or leaves a non-finite state fails with kNonFinite, and
// failure_note() names the warning.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/ode/solver.hpp"
#include "sim/pseudorigid/inputs.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/robot/robot_system.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::mujoco {

class MujocoStepper final : public ode::Stepper {
 public:
  /// MuJoCo compiles `mjcf` (robot_mjcf of s and model); throws std::invalid_argument with
  /// MuJoCo's message when it refuses it. `system` and `inputs` are the run's (read before
  /// every step); all must outlive the stepper.
  MujocoStepper(const scene::Scene& s, const robot::RobotModel& model,
                const robot::RobotSystem& system, const pseudorigid::MechanismInputs& inputs,
                const std::string& mjcf);
  ~MujocoStepper() override;
  MujocoStepper(const MujocoStepper&) = delete;
  MujocoStepper& operator=(const MujocoStepper&) = delete;

  void reset(const ode::OdeSystem& sys, double t, const ode::Vec& y) override;
  ode::StepStatus step(const ode::OdeSystem& sys, double t_limit) override;
  void dense(double t, ode::Vec& y_out) const override;
  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const ode::Vec& y() const override { return y_; }
  double h() const override { return timestep_; }
  const ode::SolverCounters& counters() const override { return counters_; }
  ode::SolverCounters& mutable_counters() override { return counters_; }
  bool can_retake() const override { return true; }
  bool retake(const ode::OdeSystem& sys, double t) override;
  std::string failure_note() const override;

  /// CPU time spent in mj_step so far, this thread [s] (the engine alone, beside the run's).
  double engine_cpu() const { return engine_cpu_; }
  /// MuJoCo's qpos and qvel now (the keyframe of an exported model).
  std::vector<double> qpos() const;
  std::vector<double> qvel() const;

 private:
  struct Impl;
  void map_in(const ode::Vec& y);
  void map_out(ode::Vec& y) const;
  void apply_inputs(const ode::Vec& y);
  /// One mj_step of length h from the current MuJoCo state; false when MuJoCo warned or the
  /// state is not finite (warning_ says which).
  bool advance(double h);
  void save_start();
  void restore_start();

  std::unique_ptr<Impl> impl_;
  const scene::Scene& scene_;
  const robot::RobotModel& model_;
  const robot::RobotSystem& system_;
  const pseudorigid::MechanismInputs& inputs_;
  double timestep_ = 1e-3;
  double t_ = 0.0, t_prev_ = 0.0;
  ode::Vec y_, y_prev_;
  ode::Vec retaken_;  ///< retake()'s state before it is accepted (no allocation per retake)
  bool started_ = false;
  ode::SolverCounters counters_;
  std::string warning_;  ///< the MuJoCo warning that failed a step (empty: none)
  double engine_cpu_ = 0.0;
  std::vector<double> target_roll_, target_pitch_;
};

}  // namespace pronk::mujoco
