#include "sim/mujoco/engine/mujoco_stepper.hpp"

#include <mujoco/mujoco.h>

#include <time.h>

#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "sim/mujoco/leg_joints.hpp"
#include "sim/mujoco/robot_mjcf.hpp"
#include "sim/pseudorigid/rigid_body.hpp"
#include "sim/run/hybrid_run.hpp"

namespace pronk::mujoco {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

/// MuJoCo's compiler keeps global state (mj_saveLastXML): one model compiles at a time.
std::mutex& compile_mutex() {
  static std::mutex m;
  return m;
}

/// MuJoCo's default error handler exits the process and its warning handler prints: errors
/// become exceptions, warnings are read from mjData.warning instead.
void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = [](const char* msg) {
      throw std::runtime_error(std::string("MuJoCo: ") + msg);
    };
    mju_user_warning = [](const char*) {};
  });
}

const char* warning_name(int w) {
  switch (w) {
    case mjWARN_INERTIA:
      return "mjWARN_INERTIA";
    case mjWARN_CONTACTFULL:
      return "mjWARN_CONTACTFULL";
    case mjWARN_CNSTRFULL:
      return "mjWARN_CNSTRFULL";
    case mjWARN_VGEOMFULL:
      return "mjWARN_VGEOMFULL";
    case mjWARN_BADQPOS:
      return "mjWARN_BADQPOS";
    case mjWARN_BADQVEL:
      return "mjWARN_BADQVEL";
    case mjWARN_BADQACC:
      return "mjWARN_BADQACC";
    case mjWARN_BADCTRL:
      return "mjWARN_BADCTRL";
    default:
      return "mjWARN_?";
  }
}

/// CPU time of the calling thread [s].
double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

int id_of(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::logic_error("MuJoCo model lacks " + name);
  return id;
}

}  // namespace

struct MujocoStepper::Impl {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  struct Leg {
    int roll_q = 0, pitch_q = 0, slide_q = 0;  // qpos addresses
    int roll_v = 0, pitch_v = 0, slide_v = 0;  // dof addresses
    int roll_eq = 0, pitch_eq = 0, motor = 0;
  };
  std::vector<Leg> legs;
  // The step's start, for retake(): MuJoCo's state and its solver's warm start.
  std::vector<mjtNum> qpos0, qvel0, warm0;
  double time0 = 0.0;
  int warnings0[mjNWARNING] = {};
  ~Impl() {
    if (d != nullptr) mj_deleteData(d);
    if (m != nullptr) mj_deleteModel(m);
  }
};

MujocoStepper::MujocoStepper(const scene::Scene& s, const robot::RobotModel& model,
                             const robot::RobotSystem& system, const pr::MechanismInputs& inputs,
                             const std::string& mjcf)
    : impl_(std::make_unique<Impl>()),
      scene_(s),
      model_(model),
      system_(system),
      inputs_(inputs),
      timestep_(s.mujoco.timestep),
      target_roll_(model.hip.size(), 0.0),
      target_pitch_(model.hip.size(), 0.0) {
  install_handlers();
  {
    std::lock_guard<std::mutex> lock(compile_mutex());
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    const char* name = "robot.xml";
    if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf.size())) != 0) {
      throw std::invalid_argument("MuJoCo: cannot hold the robot's model in its file system");
    }
    const int f = mj_findFileVFS(vfs.get(), name);
    std::memcpy(vfs->filedata[f], mjcf.data(), mjcf.size());
    char error[1000] = "";
    impl_->m = mj_loadXML(name, vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (impl_->m == nullptr) {
      throw std::invalid_argument(std::string("MuJoCo refused the robot's model: ") + error);
    }
  }
  mjModel* m = impl_->m;
  impl_->d = mj_makeData(m);
  for (size_t i = 0; i < model.hip.size(); ++i) {
    Impl::Leg L;
    const int roll = id_of(m, mjOBJ_JOINT, roll_joint_name(i));
    const int pitch = id_of(m, mjOBJ_JOINT, pitch_joint_name(i));
    const int slide = id_of(m, mjOBJ_JOINT, slide_joint_name(i));
    L.roll_q = m->jnt_qposadr[roll];
    L.pitch_q = m->jnt_qposadr[pitch];
    L.slide_q = m->jnt_qposadr[slide];
    L.roll_v = m->jnt_dofadr[roll];
    L.pitch_v = m->jnt_dofadr[pitch];
    L.slide_v = m->jnt_dofadr[slide];
    L.roll_eq = id_of(m, mjOBJ_EQUALITY, roll_hold_name(i));
    L.pitch_eq = id_of(m, mjOBJ_EQUALITY, pitch_hold_name(i));
    L.motor = id_of(m, mjOBJ_ACTUATOR, thrust_name(i));
    impl_->legs.push_back(L);
  }
  impl_->qpos0.resize(static_cast<size_t>(m->nq));
  impl_->qvel0.resize(static_cast<size_t>(m->nv));
  impl_->warm0.resize(static_cast<size_t>(m->nv));
}

MujocoStepper::~MujocoStepper() = default;

/// The run's state (rigid body, feet) into MuJoCo's qpos and qvel.
void MujocoStepper::map_in(const ode::Vec& y) {
  mjData* d = impl_->d;
  const auto& mech = model_.mechanism;
  const int jb = mech.bodies[model_.body].first_mass;
  const int rot = system_.rotation_state();
  const double M = mech.masses[static_cast<size_t>(jb)].mass;
  const Vector3d c = y.segment<3>(6 * jb);
  const Vector3d v = y.segment<3>(6 * jb + 3) / M;
  const Quaterniond q = pr::rigid_quaternion(y, rot);
  const Matrix3d R = q.toRotationMatrix();
  const Vector3d w_b = scene_.body.inertia.inverse() * (R.transpose() * y.segment<3>(rot + 4));
  for (int k = 0; k < 3; ++k) {
    d->qpos[k] = c[k];
    d->qvel[k] = v[k];
    d->qvel[3 + k] = w_b[k];
  }
  d->qpos[3] = q.w();
  d->qpos[4] = q.x();
  d->qpos[5] = q.y();
  d->qpos[6] = q.z();
  for (size_t i = 0; i < impl_->legs.size(); ++i) {
    const auto& L = impl_->legs[i];
    const int f = model_.foot[i];
    const double m_f = mech.masses[static_cast<size_t>(f)].mass;
    const Vector3d arm = R.transpose() * (y.segment<3>(6 * f) - c);
    const Vector3d r = arm - model_.hip[i];
    const Vector3d r_rate = R.transpose() * (y.segment<3>(6 * f + 3) / m_f - v) - w_b.cross(arm);
    const LegJoints j = leg_joints(r, r_rate, scene_.legs.length);
    d->qpos[L.roll_q] = j.roll;
    d->qpos[L.pitch_q] = j.pitch;
    d->qpos[L.slide_q] = j.slide;
    d->qvel[L.roll_v] = j.roll_rate;
    d->qvel[L.pitch_v] = j.pitch_rate;
    d->qvel[L.slide_v] = j.slide_rate;
  }
  mju_zero(d->qacc_warmstart, impl_->m->nv);
}

/// MuJoCo's qpos and qvel into the run's state.
void MujocoStepper::map_out(ode::Vec& y) const {
  const mjData* d = impl_->d;
  const auto& mech = model_.mechanism;
  const int jb = mech.bodies[model_.body].first_mass;
  const int rot = system_.rotation_state();
  const double M = mech.masses[static_cast<size_t>(jb)].mass;
  const Vector3d c(d->qpos[0], d->qpos[1], d->qpos[2]);
  const Vector3d v(d->qvel[0], d->qvel[1], d->qvel[2]);
  const Vector3d w_b(d->qvel[3], d->qvel[4], d->qvel[5]);
  const Quaterniond q(d->qpos[3], d->qpos[4], d->qpos[5], d->qpos[6]);
  const Matrix3d R = q.normalized().toRotationMatrix();
  y.segment<3>(6 * jb) = c;
  y.segment<3>(6 * jb + 3) = M * v;
  y[rot] = q.w();
  y[rot + 1] = q.x();
  y[rot + 2] = q.y();
  y[rot + 3] = q.z();
  y.segment<3>(rot + 4) = R * (scene_.body.inertia * w_b);
  for (size_t i = 0; i < impl_->legs.size(); ++i) {
    const auto& L = impl_->legs[i];
    LegJoints j;
    j.roll = d->qpos[L.roll_q];
    j.pitch = d->qpos[L.pitch_q];
    j.slide = d->qpos[L.slide_q];
    j.roll_rate = d->qvel[L.roll_v];
    j.pitch_rate = d->qvel[L.pitch_v];
    j.slide_rate = d->qvel[L.slide_v];
    Vector3d r, r_rate;
    foot_offset(j, scene_.legs.length, &r, &r_rate);
    const Vector3d arm = model_.hip[i] + r;
    const int f = model_.foot[i];
    const double m_f = mech.masses[static_cast<size_t>(f)].mass;
    y.segment<3>(6 * f) = c + R * arm;
    y.segment<3>(6 * f + 3) = m_f * (v + R * (w_b.cross(arm) + r_rate));
  }
}

/// The run's inputs at y (the step's start) as MuJoCo's controls, spring references and
/// equality targets.
void MujocoStepper::apply_inputs(const ode::Vec& y) {
  mjModel* m = impl_->m;
  mjData* d = impl_->d;
  const std::vector<double> force = system_.actuator_forces(y);
  for (size_t i = 0; i < impl_->legs.size(); ++i) {
    const auto& L = impl_->legs[i];
    d->ctrl[L.motor] = force[i];
    const int spring = model_.leg_spring[i];
    m->qpos_spring[L.slide_q] =
        inputs_.rest_length[static_cast<size_t>(spring)] - scene_.legs.length;
    const pr::SurfaceInputs& slide = inputs_.surfaces[static_cast<size_t>(model_.slide[i])];
    const bool line = slide.type == pr::SurfaceType::kLine;
    if (line && slide.holds) leg_angles(slide.direction, &target_roll_[i], &target_pitch_[i]);
    m->eq_active[L.roll_eq] = slide.holds ? 1 : 0;
    m->eq_active[L.pitch_eq] = line && slide.holds ? 1 : 0;
    m->eq_data[mjNEQDATA * L.roll_eq] = target_roll_[i];
    m->eq_data[mjNEQDATA * L.pitch_eq] = target_pitch_[i];
  }
}

void MujocoStepper::reset(const ode::OdeSystem&, double t, const ode::Vec& y) {
  // A restart at the state the stepper holds (an event that changed nothing) keeps MuJoCo's
  // own state; a changed one (hip placement, a lift-off, a disturbance) is mapped in.
  if (!started_ || y.size() != y_.size() || !(y.array() == y_.array()).all()) {
    map_in(y);
    // MuJoCo's forward pass at the mapped state, before the next step: that step's numbers
    // depend on it (without it they differ in the last bits; map_in cleared the warm start).
    mj_forward(impl_->m, impl_->d);
    y_ = y;  // the run's own numbers (the round trip through MuJoCo is exact to rounding)
  }
  started_ = true;
  t_ = t_prev_ = t;
  impl_->d->time = t;
  y_prev_ = y_;
}

void MujocoStepper::save_start() {
  const mjModel* m = impl_->m;
  const mjData* d = impl_->d;
  std::copy(d->qpos, d->qpos + m->nq, impl_->qpos0.begin());
  std::copy(d->qvel, d->qvel + m->nv, impl_->qvel0.begin());
  std::copy(d->qacc_warmstart, d->qacc_warmstart + m->nv, impl_->warm0.begin());
  impl_->time0 = d->time;
  for (int w = 0; w < mjNWARNING; ++w) impl_->warnings0[w] = d->warning[w].number;
}

void MujocoStepper::restore_start() {
  mjData* d = impl_->d;
  std::copy(impl_->qpos0.begin(), impl_->qpos0.end(), d->qpos);
  std::copy(impl_->qvel0.begin(), impl_->qvel0.end(), d->qvel);
  std::copy(impl_->warm0.begin(), impl_->warm0.end(), d->qacc_warmstart);
  d->time = impl_->time0;
  for (int w = 0; w < mjNWARNING; ++w) d->warning[w].number = impl_->warnings0[w];
}

bool MujocoStepper::advance(double h) {
  mjModel* m = impl_->m;
  mjData* d = impl_->d;
  m->opt.timestep = h;
  const double c0 = thread_cpu();
  mj_step(m, d);
  engine_cpu_ += thread_cpu() - c0;
  ++counters_.rhs_evaluations;
  for (int w = 0; w < mjNWARNING; ++w) {
    if (w == mjWARN_VGEOMFULL) continue;  // the viewer's, not the physics'
    if (d->warning[w].number > impl_->warnings0[w]) {
      warning_ = std::string(warning_name(w)) + ": " + mju_warningText(w, d->warning[w].lastinfo);
      return false;
    }
  }
  for (int k = 0; k < m->nq; ++k) {
    if (!std::isfinite(d->qpos[k])) {
      warning_ = "non-finite qpos";
      return false;
    }
  }
  for (int k = 0; k < m->nv; ++k) {
    if (!std::isfinite(d->qvel[k])) {
      warning_ = "non-finite qvel";
      return false;
    }
  }
  return true;
}

ode::StepStatus MujocoStepper::step(const ode::OdeSystem&, double t_limit) {
  const double h = std::min(timestep_, t_limit - t_);
  y_prev_ = y_;
  apply_inputs(y_prev_);
  save_start();
  if (!advance(h)) return ode::StepStatus::kNonFinite;
  map_out(y_);
  t_prev_ = t_;
  // The step's end on the run's clock (MuJoCo's own time is t_prev_ + h in its arithmetic).
  t_ = h == t_limit - t_ ? t_limit : t_ + h;
  ++counters_.steps_accepted;
  return ode::StepStatus::kOk;
}

bool MujocoStepper::retake(const ode::OdeSystem&, double t) {
  if (!(t > t_prev_)) return false;
  restore_start();
  apply_inputs(y_prev_);
  if (!advance(t - t_prev_)) {
    warning_.clear();
    return false;
  }
  retaken_.resize(y_.size());
  map_out(retaken_);
  if (!retaken_.allFinite()) return false;
  y_.swap(retaken_);
  t_ = t;
  return true;
}

void MujocoStepper::dense(double t, ode::Vec& y_out) const {
  const double span = t_ - t_prev_;
  const double a = span > 0.0 ? (t - t_prev_) / span : 1.0;
  y_out = y_prev_ + a * (y_ - y_prev_);
}

std::string MujocoStepper::failure_note() const {
  std::string note = std::string("MuJoCo ") + integrator_name(scene_.mujoco.integrator) +
                     ", step " + run::fmt(timestep_) + " s";
  if (!warning_.empty()) note += "; " + warning_;
  return note;
}

std::vector<double> MujocoStepper::qpos() const {
  return {impl_->d->qpos, impl_->d->qpos + impl_->m->nq};
}

std::vector<double> MujocoStepper::qvel() const {
  return {impl_->d->qvel, impl_->d->qvel + impl_->m->nv};
}

}  // namespace pronk::mujoco
