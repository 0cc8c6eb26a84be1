// simulate(): the robot scene in the full model, on the method the scene names or the one
// "auto" chooses (checked, and rerun once tighter when it missed its accuracy).

#include "sim/robot/robot_simulator.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>

#include "sim/mujoco/mujoco_simulator.hpp"
#include "sim/pseudorigid/scene_probe.hpp"
#include "sim/reduced/run_limits.hpp"
#include "sim/robot/feet_step_bound.hpp"
#include "sim/robot/robot_run.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;
using detail::RobotRun;

namespace {

constexpr double kFlightStep = 5e-3;  ///< quasi-static feet under auto: flight's largest step [s]

/// Auto's choice written into the scene's solver settings and the built model's solver.
void apply_to_scene(const pr::MethodChoice& c, scene::Scene* scene, RobotModel* model) {
  scene::PseudoRigid& p = scene->pseudo_rigid;
  pr::apply_choice(c, &p.solver, &p.energy_tol);
  p.solver_auto = false;
  model->mechanism.simulation.solver = p.solver;
}

/// "method": "auto": the scene with the method chosen for its built robot (model's solver
/// updated as build_robot sets it); the choice in *choice.
scene::Scene with_chosen_method(const scene::Scene& scene, RobotModel* model,
                                pr::MethodChoice* choice) {
  scene::Scene chosen = scene;
  scene::PseudoRigid& p = chosen.pseudo_rigid;
  pr::AutoRequest request;
  request.accuracy = p.accuracy;
  request.h_max = p.solver.h_max;
  request.t_end = scene.simulation.duration;
  request.restarts = true;  // touchdowns, apexes, foot switches
  if (model->quasi_static_feet) {
    // The stiff modes are the body's on its landed feet (feet_step_bound.hpp), which the
    // mechanism (the body alone) does not have: probed as contacts with that frequency.
    // - Stance: the body rings on its landed feet (the slots and the creep in series, a
    //   Maxwell element of about half a stance, as on 1 g feet), and near the stability bound
    //   (omega h = 1.4) Verlet is stable but far from that ringing: the step resolves it.
    // - Flight (every foot in the air, every hip locked): nothing acts on the body but
    //   gravity and its own springs (four masses; none on the rigid body), so flight takes
    //   the body's own verlet step (0.7 x 2 / omega_body) up to kFlightStep: its accuracy is
    //   the events' (a touchdown located on the dense output).
    pr::SceneProbe probe = pr::probe_scene(model->mechanism);
    const double omega_body = probe.omega_max;  // the body's own springs (none if rigid)
    probe.omega_max = probe.omega_bound = request.resolve_omega = quasi_static_omega(scene, *model);
    probe.contact = probe.dissipation = probe.dissipation_split = true;
    request.flight_step = std::min(kFlightStep, request.h_max);
    if (omega_body > 0.0) {
      request.flight_step = std::min(request.flight_step, pr::round_down_2(0.7 * 2.0 / omega_body));
    }
    *choice = pr::choose_method(probe, request);
  } else {
    *choice = pr::choose_method(model->mechanism, request);
  }
  apply_to_scene(*choice, &chosen, model);
  return chosen;
}

/// A fixed verlet step past the quasi-static feet's stability bound (feet_step_bound.hpp).
std::optional<reduced::LimitBreach> feet_step_breach(const scene::Scene& scene,
                                                     const RobotModel& model,
                                                     const ode::SolverOptions& solver) {
  if (!model.quasi_static_feet || solver.method != ode::Method::kVerlet) return std::nullopt;
  // Flight: the body's own springs (four masses; none on the rigid body).
  const double omega_body = pr::probe_scene(model.mechanism).omega_max;
  if (omega_body > 0.0 && solver.h_flight > 2.0 / omega_body) {
    reduced::LimitBreach b;
    b.field = "h_flight";
    b.found = "verlet flight step " + run::fmt(solver.h_flight) + " s";
    b.expected = "at most the body's own stability bound 2/omega = " + run::fmt(2.0 / omega_body) +
                 " s (omega = " + run::fmt(omega_body) +
                 " rad/s: its springs, every foot in the air)";
    return b;
  }
  const double omega = quasi_static_omega(scene, model);
  if (!(solver.h_fixed > 2.0 / omega)) return std::nullopt;
  reduced::LimitBreach b;
  b.field = "h_fixed";
  b.found = "verlet step " + run::fmt(solver.h_fixed) + " s";
  b.expected =
      "at most the quasi-static feet's stability bound 2/omega = " + run::fmt(2.0 / omega) +
      " s (omega = " + run::fmt(omega) +
      " rad/s: the body on its landed feet's slot and leg springs)";
  return b;
}

/// One run of the built robot on the scene's solver.
RobotRunResult run_once(const scene::Scene& scene, const RobotModel& model,
                        const RobotRunOptions& options, bool automatic,
                        const pr::MethodChoice& choice) {
  auto robot = std::make_unique<RobotRun>(scene, model, options);
  robot->result.monitors.method_auto = automatic;
  robot->result.monitors.method_choice = choice;
  auto stepper = ode::make_stepper(robot->solver(), robot->dimension(), robot->error_norm());
  ode::Vec y = robot->initial_state();
  robot->prepare(y);
  auto too_long = reduced::fixed_step_breach(scene, robot->solver());
  if (!too_long) too_long = feet_step_breach(scene, model, robot->solver());
  const run::HybridEnd end = too_long ? robot->refuse(*stepper, y, too_long->reason())
                                      : run::run_hybrid(*robot, *stepper, 0.0, y);
  robot->finish(end.t, end.y, *stepper);
  return std::move(robot->result);
}

}  // namespace

RobotRunResult simulate(const scene::Scene& scene_in, const RobotRunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  reduced::require_memory_limits(scene_in.simulation, options.record_trajectory, true);
  if (scene_in.model == scene::ModelKind::kMujoco) {
#ifdef PRONK_HAVE_MUJOCO
    RobotRunResult result = mujoco::simulate(scene_in, options);
    result.run.cost.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return result;
#else
    throw std::invalid_argument(mujoco::kNotBuilt);
#endif
  }
  RobotModel model = build_robot(scene_in);
  pr::MethodChoice choice;
  const bool automatic = scene_in.pseudo_rigid.solver_auto;
  scene::Scene chosen;  // the scene with auto's choice (no copy otherwise)
  if (automatic) chosen = with_chosen_method(scene_in, &model, &choice);
  RobotRunResult result =
      run_once(automatic ? chosen : scene_in, model, options, automatic, choice);
  // Auto checks its run: a completed run that missed the accuracy is rerun once, tighter
  // (method_choice.hpp, refine_choice); the cost reported is both runs'.
  if (automatic && result.run.status == reduced::RunStatus::kCompleted &&
      pr::needs_rerun(choice, result.monitors.drift_relative())) {
    choice = pr::refine_choice(choice, result.monitors.drift_relative());
    apply_to_scene(choice, &chosen, &model);
    const ode::SolverCounters first = result.run.cost.solver;
    result = run_once(chosen, model, options, automatic, choice);
    result.run.cost.solver += first;
  }
  result.run.cost.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace pronk::robot
