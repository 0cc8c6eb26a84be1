#include "sim/robot/robot_system.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "sim/ode/difference_jacobian.hpp"
#include "sim/pseudorigid/rigid_body.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;
using Eigen::Vector3d;

RobotSystem::RobotSystem(const RobotModel& model, const pr::MechanismInputs& inputs,
                         const scene::PseudoRigid& settings)
    : model_(model),
      settings_(settings),
      sys_(model.mechanism, inputs),
      force_(model.hip.size(), 0.0),
      push_(model.hip.size(), Vector3d::UnitZ()),
      free_(model.hip.size(), false),
      fb_(model.hip.size(), 0.0) {
  for (const auto& ms : model.mechanism.masses) inv_mass_.push_back(1.0 / ms.mass);
  rotation_ = sys_.rotation_state(model.body);
  mech_dim_ = sys_.dimension();
  body_first_ = 6 * model.mechanism.bodies[model.body].first_mass;
  extra_ = fp_ = fm_ = ode::Vec::Zero(actuator_force_size());
  if (model.quasi_static_feet) {
    qs_states_ = 2 * static_cast<int>(model.hip.size());
    rest_ = model.rest_length;
    dir_ = model.direction;
    slot_.assign(model.hip.size(), {Vector3d::UnitY(), Vector3d::Zero()});
    locked_ = !settings.hip_rotation;
    pinned_.assign(model.hip.size(), false);
    mu_ = settings.friction;
    v_slip_ = settings.slip_velocity;
    k_leg_ = settings.leg_stiffness;
    k_slot_ = settings.internal_stiffness;
    k_ground_ = settings.contact_stiffness;
    c_leg_ = settings.leg_damping;
    land_force_ = 1e-3 * model.mechanism.total_mass() * -model.mechanism.gravity.z() /
                  static_cast<double>(model.hip.size());
  }
}

int RobotSystem::actuator_force_size() const {
  return 3 * static_cast<int>(inv_mass_.size()) + (rotation_ >= 0 ? 3 : 0);
}

Vector3d RobotSystem::push_world(size_t i, const ode::Vec& y) const {
  return push_world(i, y, sys_.frames(y)[model_.body].rotation);
}

Vector3d RobotSystem::push_world(size_t i, const ode::Vec& y, const Eigen::Matrix3d& R) const {
  if (!free_[i] || (model_.foot[i] < 0 && qs_states_ == 0)) return R * push_[i];
  if (pinned(i)) {  // (the stance's foot -> hip line, as below)
    const Stance& st = stance_at(i, y);
    if (st.l > 1e-12) return st.d;
  }
  const Vector3d d = sys_.node_position(model_.hip_node[i], y) - foot_position(i, y);
  const double len = d.norm();
  return len > 1e-12 ? Vector3d(d / len) : Vector3d(R * push_[i]);
}

const Eigen::VectorXd& RobotSystem::min_norm_solve(const Eigen::MatrixXd& A,
                                                   const Vector3d& b) const {
  // f = A^T (A A^T)^-1 b while A A^T is well conditioned (the legs' moment arms span the
  // plane); otherwise the complete orthogonal decomposition's minimum-norm solution.
  const Eigen::Matrix3d M = A * A.transpose();
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(M);
  const Vector3d d = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() == Eigen::Success && ldlt.isPositive() && d.minCoeff() > 1e-12 * d.maxCoeff()) {
    f_ = A.transpose() * ldlt.solve(b);
  } else {
    f_ = A.completeOrthogonalDecomposition().solve(b);
  }
  return f_;
}

bool RobotSystem::feedback(const ode::Vec& y) const {
  if (qs_states_ == 0) return stance_feedback(y);
  // Quasi-static feet read the feedback at every foot's balance: memoised on the state (its
  // inputs' setters drop the memo).
  if (!fb_memo_) fb_memo_count_ = fb_memo_next_ = 0;
  for (int k = 0; k < fb_memo_count_; ++k) {
    const FeedbackMemo& m = fb_memo_entries_[static_cast<size_t>(k)];
    if (m.y.size() == y.size() && (m.y.array() == y.array()).all()) {
      std::copy(m.fb.begin(), m.fb.end(), fb_.begin());
      return m.on;
    }
  }
  FeedbackMemo& m = fb_memo_entries_[static_cast<size_t>(fb_memo_next_)];
  m.on = stance_feedback(y);
  m.y = y;
  m.fb = fb_;
  fb_memo_next_ = (fb_memo_next_ + 1) % kFeedbackMemo;
  fb_memo_count_ = std::min(fb_memo_count_ + 1, kFeedbackMemo);
  fb_memo_ = true;
  return m.on;
}

bool RobotSystem::stance_feedback(const ode::Vec& y) const {
  std::fill(fb_.begin(), fb_.end(), 0.0);
  if (!settings_.stance_feedback() || !settings_.actuators) return false;
  std::vector<size_t>& g = grounded_;
  g.clear();
  for (size_t i = 0; i < free_.size(); ++i) {
    if (free_[i] && (model_.foot[i] >= 0 || qs_states_ > 0)) g.push_back(i);
  }
  if (g.size() < 3) return false;  // partial landings: no differential push
  const pr::BodyFrame& fr = sys_.frames(y)[model_.body];
  const Eigen::Matrix3d R = fr.rotation;
  const Vector3d com = fr.com;
  // Tilt of the body z axis from the vertical as a rotation vector (body frame) and
  // the body angular velocity (body frame).
  const Vector3d zb = R.col(2);
  const Vector3d axis = zb.cross(Vector3d::UnitZ());
  const double s = axis.norm();
  const Vector3d tilt =
      s > 1e-15 ? Vector3d(R.transpose() * axis * (std::atan2(s, zb.z()) / s)) : Vector3d::Zero();
  const Vector3d w = R.transpose() * sys_.body_omega(model_.body, y);
  Eigen::Vector3d b(0.0, 0.0, 0.0);  // moment about body x, y [N m]; net push 0
  for (int k = 0; k < 2; ++k) {
    b[k] = settings_.stance_kp[k] * (tilt[k] + stance_tilt_[k]) - settings_.stance_kd[k] * w[k];
    // Smooth saturation at the moment limit.
    const double m = settings_.stance_max_moment;
    if (m > 0.0) b[k] = m * std::tanh(b[k] / m);
  }
  // Minimum-norm leg forces giving that moment with no net force along the legs'
  // mean direction: A f = b, A = [(r_i x u_i)_x; (r_i x u_i)_y; u_i . n] (body frame).
  Eigen::MatrixXd& A = A_;  // (scratch: no allocation once sized)
  A.resize(3, static_cast<int>(g.size()));
  std::vector<Vector3d>& u = u_;
  u.resize(g.size());
  Vector3d n = Vector3d::Zero();
  for (size_t k = 0; k < g.size(); ++k) {
    u[k] = push_world(g[k], y, R);
    n += u[k];
  }
  n.normalize();
  for (size_t k = 0; k < g.size(); ++k) {
    const Vector3d r = sys_.node_position(model_.hip_node[g[k]], y) - com;
    const Vector3d m = R.transpose() * r.cross(u[k]);
    A(0, static_cast<int>(k)) = m.x();
    A(1, static_cast<int>(k)) = m.y();
    A(2, static_cast<int>(k)) = u[k].dot(n);
  }
  const Eigen::VectorXd& f = min_norm_solve(A, b);
  // A leg can only pull its foot as far as its spring pushes it: the total actuator
  // force stays above minus the spring force (or the set force, if lower), so a foot
  // just landed is not lifted off again.
  for (size_t k = 0; k < g.size(); ++k) {
    const size_t i = g[k];
    const double length =
        pinned(i) ? stance_at(i, y).l
                  : (sys_.node_position(model_.hip_node[i], y) - foot_position(i, y)).norm();
    const double rest = qs_states_ > 0
                            ? rest_[i]
                            : sys_.inputs().rest_length[static_cast<size_t>(model_.leg_spring[i])];
    const double spring = settings_.leg_stiffness * std::max(0.0, rest - length);
    fb_[i] = std::max(f[static_cast<int>(k)], std::min(0.0, -spring - force_[i]));
  }
  return true;
}

std::vector<double> RobotSystem::actuator_forces(const ode::Vec& y) const {
  std::vector<double> out = force_;
  if (feedback(y)) {
    for (size_t i = 0; i < out.size(); ++i) out[i] += fb_[i];
  }
  for (double& f : out) f *= settings_.actuator_gain;
  return out;
}

bool RobotSystem::extra_forces(const ode::Vec& y, ode::Vec& f) const {
  const bool fb = feedback(y);
  bool any = fb;
  for (size_t i = 0; i < force_.size(); ++i) any = any || force_[i] != 0.0;
  if (!any) return false;
  f.setZero();
  const auto& body = model_.mechanism.bodies[model_.body];
  const Eigen::Matrix3d R = sys_.frames(y)[model_.body].rotation;
  for (size_t i = 0; i < force_.size(); ++i) {
    double fi = settings_.actuator_gain * (force_[i] + fb_[i]);
    if (settings_.actuator_max_force > 0.0) {
      fi = std::clamp(fi, -settings_.actuator_max_force, settings_.actuator_max_force);
    }
    if (fi == 0.0) continue;
    if (qs_states_ > 0 && !pinned_[i]) continue;  // a massless foot in the air: nothing to push
    const Vector3d F = fi * push_world(i, y, R);  // on the body at the hip
    const pr::NodeRef& h = model_.hip_node[i];
    if (rotation_ >= 0) {  // rigid body: on its CoM mass, and the torque after the masses'
      const Vector3d com = y.segment<3>(6 * body.first_mass);
      f.segment<3>(3 * body.first_mass) += F;
      f.segment<3>(3 * static_cast<int>(inv_mass_.size())) +=
          (sys_.node_position(h, y) - com).cross(F);
    } else if (h.kind == pr::NodeRef::Kind::kMass) {
      f.segment<3>(3 * h.index) += F;
    } else {
      const auto& g = model_.mechanism.ghost_points[h.index];
      for (int k = 0; k < 4; ++k) f.segment<3>(3 * (body.first_mass + k)) += g.weights[k] * F;
    }
    if (model_.foot[i] >= 0) f.segment<3>(3 * model_.foot[i]) -= F;
  }
  return true;
}

void RobotSystem::add_extra(const ode::Vec& y, ode::Vec& dydt) const {
  if (!extra_forces(y, extra_)) return;
  const int nm = static_cast<int>(inv_mass_.size());
  for (int j = 0; j < nm; ++j) dydt.segment<3>(6 * j + 3) += extra_.segment<3>(3 * j);
  if (rotation_ >= 0) dydt.segment<3>(rotation_ + 4) += extra_.segment<3>(3 * nm);
}

void RobotSystem::rhs(double t, const ode::Vec& y, ode::Vec& dydt) const {
  sys_.rhs(t, y, dydt);
  add_extra(y, dydt);
  if (qs_states_ > 0) add_feet(y, /*damped=*/true, /*rates=*/true, dydt);
}

void RobotSystem::conservative_rhs(double t, const ode::Vec& y, ode::Vec& dydt) const {
  sys_.conservative_rhs(t, y, dydt);
  add_extra(y, dydt);
  if (qs_states_ > 0) add_feet(y, /*damped=*/false, /*rates=*/false, dydt);
}

void RobotSystem::momentum_mask(ode::Vec& mask) const {
  sys_.momentum_mask(mask);
  if (qs_states_ == 0) return;
  mask.conservativeResize(dimension());
  mask.tail(qs_states_).setZero();  // the feet's states are neither positions nor momenta
}

void RobotSystem::position_rate(const ode::Vec& y, ode::Vec& dydt) const {
  sys_.position_rate(y, dydt);
  if (qs_states_ > 0) dydt.tail(qs_states_).setZero();  // (relax() moves them)
}

void RobotSystem::jacobian(double t, const ode::Vec& y, Eigen::SparseMatrix<double>& J) const {
  if (rotation_ >= 0 || qs_states_ > 0) {
    // rigid body, or quasi-static feet: forward differences of the whole RHS, actuators and
    // feet included
    ode::difference_jacobian(*this, t, y, J);
    return;
  }
  sys_.jacobian(t, y, J);
  if (!extra_forces(y, extra_)) return;
  // Columns the actuator forces read: the body masses' positions (attitude turns the
  // forces) and, with the feedback, their momenta (angular velocity); a free leg's push
  // direction follows its foot (and a dummy hip mass).
  std::vector<int> cols;
  const int first = model_.mechanism.bodies[model_.body].first_mass;
  const bool fb = feedback(y);
  for (int k = 0; k < 4; ++k) {
    for (int c = 0; c < (fb ? 6 : 3); ++c) cols.push_back(6 * (first + k) + c);
  }
  for (size_t i = 0; i < force_.size(); ++i) {
    if ((force_[i] == 0.0 && !fb) || !free_[i] || model_.foot[i] < 0) continue;
    for (int c = 0; c < 3; ++c) cols.push_back(6 * model_.foot[i] + c);
    const pr::NodeRef& h = model_.hip_node[i];
    if (h.kind == pr::NodeRef::Kind::kMass) {
      for (int c = 0; c < 3; ++c) cols.push_back(6 * h.index + c);
    }
  }
  std::sort(cols.begin(), cols.end());  // each column once (central differences add up)
  cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
  triplets_.clear();
  yp_ = y;
  const int nm = static_cast<int>(inv_mass_.size());
  for (int col : cols) {
    const double h = 1e-7 * (1.0 + std::abs(y[col]));
    yp_[col] = y[col] + h;
    extra_forces(yp_, fp_);
    yp_[col] = y[col] - h;
    extra_forces(yp_, fm_);
    yp_[col] = y[col];
    for (int j = 0; j < nm; ++j) {
      for (int k = 0; k < 3; ++k) {
        const double d = (fp_[3 * j + k] - fm_[3 * j + k]) / (2.0 * h);
        if (d != 0.0) triplets_.emplace_back(6 * j + 3 + k, col, d);
      }
    }
  }
  if (triplets_.empty()) return;
  Eigen::SparseMatrix<double> E(J.rows(), J.cols());
  E.setFromTriplets(triplets_.begin(), triplets_.end());
  J += E;
}

double RobotSystem::actuator_power(const ode::Vec& y) const {
  if (!extra_forces(y, extra_)) return 0.0;
  const int nm = static_cast<int>(inv_mass_.size());
  double total = 0.0;
  for (int j = 0; j < nm; ++j) {
    total += extra_.segment<3>(3 * j).dot(y.segment<3>(6 * j + 3) * inv_mass_[j]);
  }
  if (rotation_ >= 0) total += extra_.segment<3>(3 * nm).dot(sys_.body_omega(model_.body, y));
  return total;
}

std::vector<Vector3d> RobotSystem::friction_forces(const ode::Vec& y) const {
  std::vector<Vector3d> out(model_.foot.size(), Vector3d::Zero());
  if (qs_states_ > 0) {
    feedback(y);
    for (size_t i = 0; i < out.size(); ++i) out[i] = ground_reaction(i, y, false);
    for (Vector3d& f : out) f.z() = 0.0;
    return out;
  }
  if (model_.ground < 0) return out;
  for (size_t i = 0; i < model_.foot.size(); ++i) {
    const pr::NodeRef foot{pr::NodeRef::Kind::kMass, model_.foot[i]};
    out[i] = sys_.contact(model_.ground, foot, y).friction;
  }
  return out;
}

std::vector<double> RobotSystem::normal_forces(const ode::Vec& y) const {
  std::vector<double> out(model_.foot.size(), 0.0);
  if (qs_states_ > 0) {
    feedback(y);
    for (size_t i = 0; i < out.size(); ++i)
      out[i] = std::max(0.0, ground_reaction(i, y, false).z());
    return out;
  }
  if (model_.ground < 0) return out;
  for (size_t i = 0; i < model_.foot.size(); ++i) {
    const pr::NodeRef foot{pr::NodeRef::Kind::kMass, model_.foot[i]};
    out[i] = sys_.contact(model_.ground, foot, y).normal;
  }
  return out;
}

}  // namespace pronk::robot
