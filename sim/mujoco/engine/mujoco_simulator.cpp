// mujoco::simulate(): the robot run of the full model (RobotRun: events, controller, records)
// stepped by MuJoCo (MujocoStepper) on the scene's robot as MJCF (robot_mjcf.hpp).

#include "sim/mujoco/mujoco_simulator.hpp"

#include <memory>
#include <stdexcept>

#include "sim/mujoco/engine/mujoco_stepper.hpp"
#include "sim/mujoco/robot_mjcf.hpp"
#include "sim/robot/robot_run.hpp"
#include "sim/scene/mujoco_scene.hpp"

namespace pronk::mujoco {

namespace {

/// The scene as the run loop takes it: the body rigid (MuJoCo's body is), events restarted on
/// MuJoCo's own trajectory (retaken steps), no automatic method (MuJoCo steps).
scene::Scene engine_scene(const scene::Scene& s) {
  scene::Scene e = s;
  scene::PseudoRigid& p = e.pseudo_rigid;
  p.body = scene::PseudoRigid::BodyKind::kRigid;
  p.hips = scene::PseudoRigid::Hips::kGhost;
  p.solver_auto = false;
  p.solver = scene::PseudoRigid::default_solver();
  p.solver.method = ode::Method::kDopri5;  // (the run's bookkeeping; MuJoCo steps)
  p.solver.event_restart = ode::EventRestart::kStep;
  p.solver.h_max = s.mujoco.timestep;
  return e;
}

}  // namespace

robot::RobotRunResult simulate(const scene::Scene& scene_in,
                               const robot::RobotRunOptions& options) {
  // (the loader refuses these; a map study sets its cells' model itself)
  if (const auto r = scene::mujoco_refusal(scene_in)) {
    throw std::invalid_argument("MuJoCo cannot run this scene: " + r->pointer + ": expected " +
                                r->expected + ", found " + r->found);
  }
  const scene::Scene s = engine_scene(scene_in);
  const robot::RobotModel model = robot::build_robot(s);
  auto run = std::make_unique<robot::detail::RobotRun>(s, model, options);
  run->external_engine();
  MujocoStepper stepper(s, model, run->robot_system(), run->inputs(), robot_mjcf(s, model));
  ode::Vec y = run->initial_state();
  run->prepare(y);
  stepper.reset(run->robot_system(), 0.0, y);
  const std::string mjcf = robot_mjcf(s, model, stepper.qpos(), stepper.qvel());
  const run::HybridEnd end = run::run_hybrid(*run, stepper, 0.0, y);
  run->finish(end.t, end.y, stepper);
  robot::RobotRunResult result = std::move(run->result);
  result.mjcf = mjcf;
  result.engine_cpu = stepper.engine_cpu();
  return result;
}

}  // namespace pronk::mujoco
