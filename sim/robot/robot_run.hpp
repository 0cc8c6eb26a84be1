// One robot run on the hybrid loop (RobotRun): the run's segments, events and switches; its
// member functions live by concern in robot_run.cpp (events, strides, disturbances, the end),
// leg_actuation.cpp (actuators and thrust), feet.cpp (landing, lift-off) and
// leg_placement.cpp (hip placement in flight).
#pragma once

#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sim/ode/solver.hpp"
#include "sim/reduced/run_record.hpp"
#include "sim/robot/control_layers.hpp"
#include "sim/robot/robot_events.hpp"
#include "sim/robot/robot_simulator.hpp"
#include "sim/robot/robot_system.hpp"
#include "sim/robot/run_data.hpp"
#include "sim/robot/run_monitor.hpp"
#include "sim/robot/step_observer.hpp"
#include "sim/run/hybrid_run.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

/// The run's solver options: the scene's, with verlet's energy budget in joules
/// (energy_tol x the energy scale [J]).
ode::SolverOptions solver_options(const scene::PseudoRigid& prs, double energy_scale);

/// " (METHOD step H s[; verlet's stability bound])": the numbers of a divergence.
/// verlet_limit: 2 / (a bound on the highest spring frequency) [s], 0 for other methods.
std::string divergence_note(ode::Method method, double h, double verlet_limit);

/// One robot run on the hybrid loop: flight, stance and (spring legs) armed segments;
/// touchdown (the controller plans the stance and commands the actuators), the bottom of a
/// spring stance (the actuators fire), apex (hip placement, hop-height feedback), feet
/// landing and lifting off (free stance hips), actuators switching off, disturbances,
/// falls and energy blow-up.
class RobotRun final : public run::HybridModel {
 public:
  enum { kTouchdown = 0, kApex = 1, kFallLow = 2, kFallTilt = 3, kBottom = 4, kFoot = 5 };

  RobotRun(const scene::Scene& scene, const RobotModel& model, const RobotRunOptions& options);

  /// The stepper's options (verlet's energy budget in joules).
  const ode::SolverOptions& solver() const { return solver_; }
  int dimension() const { return sys_.dimension(); }
  ode::ErrorNorm error_norm() const { return sys_.error_norm(); }
  ode::Vec initial_state() const { return sys_.initial_state(); }
  /// Before the run: a run starting in the air places its legs for the first touchdown.
  void prepare(ode::Vec& y) {
    if (model_.spring_legs && prs_.hip_rotation) place_legs(0.0, y);
  }
  /// The run's records at its end (t, y).
  void finish(double t, const ode::Vec& y, const ode::Stepper& stepper);
  /// A run the fixed-step rule refuses (reduced/run_limits.hpp): `diverged` at t = 0 with
  /// the reason, the initial sample kept.
  run::HybridEnd refuse(ode::Stepper& stepper, const ode::Vec& y0, std::string reason) {
    stepper.reset(sys_, 0.0, y0);
    start(stepper, y0);
    end_run(reduced::RunStatus::kDiverged, std::move(reason));
    return {0.0, y0};
  }

  /// The run's system and inputs (an engine that steps on its own reads them before a step).
  const RobotSystem& robot_system() const { return sys_; }
  const pr::MechanismInputs& inputs() const { return data_.inputs; }
  /// Another engine integrates (MuJoCo): its contact and dampers are not the pseudo-rigid
  /// model's, so the model's energy balance along its trajectory measures the two models'
  /// difference, not an integration error, and ends no run (energy_drift still reports it).
  void external_engine() {
    blowup_ = std::numeric_limits<double>::infinity();
    run_.blowup = blowup_;
    result.monitors.energy_measured = false;
  }

  const ode::OdeSystem& system() const override { return sys_; }
  const ode::SolverOptions& integration_options() const override { return prs_.solver; }
  void start(const ode::Stepper& stepper, const ode::Vec& y) override {
    observer_.start(stepper, y);
  }
  double segment_end(double) const override {
    double t_target = scene_.simulation.duration;
    if (next_disturbance_ < scene_.disturbances.size()) {
      t_target = std::min(t_target, scene_.disturbances[next_disturbance_].time);
    }
    if (run_.stance) {
      for (size_t i = 0; i < legs_; ++i) {
        if (data_.leg_force[i] != 0.0) t_target = std::min(t_target, data_.off_time[i]);
      }
    }
    return t_target;
  }
  std::span<const ode::EventFunction* const> events() const override {
    return data_.armed ? armed_events_ : run_.stance ? stance_events_ : flight_events_;
  }
  ode::StepObserver* observer() override { return &observer_; }
  void on_failure(const run::Segment& seg, const ode::Vec&, const ode::Stepper& st) override {
    end_run(reduced::RunStatus::kDiverged,
            run::failure_reason(seg, st, prs_.solver, step_note(st)));
  }
  run::Next on_segment_end(const run::Segment& seg, ode::Vec& y,
                           const ode::Stepper& stepper) override;
  void on_restart() override { observer_.restart(); }
  /// Quasi-static feet on method verlet with a flight step (SolverOptions::h_flight): the
  /// flight step while every foot is in the air and every hip locked (nothing but gravity
  /// acts on a rigid body then), h_fixed otherwise.
  double fixed_step(double t, const ode::Vec& y) const override;

  RobotRunResult result;

 private:
  const std::vector<int>& event_ids() const {
    return data_.armed ? armed_ids_ : run_.stance ? stance_ids_ : flight_ids_;
  }
  void end_run(reduced::RunStatus status, std::string reason) {
    result.run.status = status;
    result.run.reason = std::move(reason);
  }
  std::string step_note(const ode::Stepper& st) const {
    const std::string engine = st.failure_note();
    return engine.empty() ? divergence_note(solver_.method, st.h(), verlet_limit_)
                          : " (" + engine + ")";
  }
  Vector3d total_momentum(const ode::Vec& ys) const {
    Vector3d p = Vector3d::Zero();
    for (size_t j = 0; j < model_.mechanism.masses.size(); ++j) p += ys.segment<3>(6 * j + 3);
    return p;
  }
  /// Everything the legs and the ground gave since touchdown (gravity removed) [N s].
  Vector3d delivered(double t, const ode::Vec& y) const {
    return total_momentum(y) - p_touchdown_ +
           Vector3d(0, 0, total_mass_ * g_ * (t - current_.t_touchdown));
  }
  void finish_stride(double t_next) {
    if (!have_stride_) return;
    reduced::close_stride(current_, t_next);
    result.run.strides.push_back(current_);
    result.stride_actuator_force.push_back(data_.stride_force);
    result.stride_slip.push_back(run_.stride_slip);
    result.stride_contact.push_back(data_.spring_stance);
    have_stride_ = false;
  }
  void set_actuators() { sys_.set_actuators(data_.leg_force, data_.push); }
  /// The body state as the sensors read it: roll and pitch offset by the attitude sensor's
  /// bias (pseudo_rigid.attitude_sensor_bias).
  control::BodyState sensed(control::BodyState s) const {
    if (!prs_.attitude_sensor_bias.isZero()) tilt(prs_.attitude_sensor_bias, s);
    return s;
  }
  /// The body state the controller sees: the sensed one, position, roll and pitch offset by
  /// the integral actions.
  control::BodyState trimmed(control::BodyState s) const {
    s.position.head<2>() += data_.position_trim.head<2>();
    if (prs_.attitude_trim_gain > 0.0) tilt(data_.attitude_trim, s);
    return s;
  }
  /// Offsets the roll and pitch of s by d [rad], its attitude and rotation with them.
  static void tilt(const Eigen::Vector2d& d, control::BodyState& s) {
    s.euler123.head<2>() += d;
    s.attitude = math::euler_to_quat(s.euler123, math::EulerSet::k123);
    s.rotation = s.attitude.toRotationMatrix();
  }
  void book_work(double e_before, const ode::Vec& y) {
    book_hip_work(result.monitors, sys_.energies(y).total() - e_before);
  }
  bool energy_ok(double t, const ode::Vec& y, const ode::Stepper& stepper);
  void on_apex(double t, ode::Vec& y);
  run::Next on_touchdown(double t, const ode::Vec& y);
  double command_actuators(const control::StancePlan& plan, double t);
  void on_bottom(double t, const ode::Vec& y);
  double energy_thrust(double t, const ode::Vec& y);
  void on_foot(size_t first, double t, ode::Vec& y);
  void lift_foot(size_t i, ode::Vec& y);
  void quasi_static_switch(size_t i, bool crossed, ode::Vec& y);
  void catch_up_feet(double t, ode::Vec& y);
  bool quasi_static_due(size_t i, const ode::Vec& y) const;
  run::Next on_time(double t, ode::Vec& y);
  void apply_disturbance(const scene::Disturbance& d, ode::Vec& y);
  void place_legs(double t, ode::Vec& y);
  std::vector<Vector3d> placement(double t, const ode::Vec& y, control::BodyState& s,
                                  Matrix3d& R_td);
  std::vector<double> level_rest_lengths(const control::BodyState& s, const Matrix3d& R_td,
                                         const std::vector<Vector3d>& u) const;

  const scene::Scene& scene_;
  /// The scene as the controller sees it: the robot's nominal numbers when a robust-design
  /// scenario perturbed the robot (scene::ControllerModel). The controller layers, the
  /// stance-time estimate, the thrust law and the leg controllers read it; the dynamics the scene.
  const scene::Scene belief_;
  const RobotModel& model_;
  const scene::PseudoRigid& prs_;
  const size_t legs_;
  const double g_, l_;
  RunData data_;
  RobotSystem sys_;
  const pr::MechanismSystem& msys_;
  const ControlLayers control_;
  RunMonitor run_;
  Observer observer_;
  ComHeightEvent touchdown_, fall_low_;
  ApexEvent apex_;
  TiltEvent fall_tilt_;
  BottomEvent bottom_;
  std::vector<std::unique_ptr<FootEvent>> foot_events_;
  std::vector<const ode::EventFunction*> flight_events_, stance_events_, armed_events_;
  std::vector<int> flight_ids_, stance_ids_, armed_ids_;
  /// Rotating hips are driven in flight (they place the legs) and free about their
  /// pitch axis in stance: a landed foot's slide (a line) becomes a slot (a bilateral
  /// plane through the hip containing the leg and the body x axis), so the leg swings
  /// fore-aft over its gripped foot as a strut (spring, damper and actuator along the
  /// hip-foot line) while ab/adduction stays held; at lift-off the slide takes the
  /// leg again along its current direction. (Fully free hips, no slot, were tried:
  /// the four pinned struts make yaw unstable, ~3x per stride.)
  const bool free_stance_;
  double total_mass_ = 0.0, balance0_ = 0.0, blowup_ = 0.0;
  ode::SolverOptions solver_;
  double verlet_limit_ = 0.0;

  reduced::StrideRecord current_;
  bool have_stride_ = false;
  long touchdowns_ = 0, touchdown_events_ = 0;
  Vector3d p_touchdown_ = Vector3d::Zero();
  size_t next_disturbance_ = 0;
};

}  // namespace pronk::robot::detail
