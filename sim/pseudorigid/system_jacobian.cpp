// MechanismSystem's analytic sparse Jacobian: 3x3 blocks through the node transfers, the
// connections' and applied forces' blocks (the surfaces' are in system_surfaces.cpp), and
// its check against central differences.
#include <algorithm>
#include <array>
#include <cmath>

#include "sim/ode/difference_jacobian.hpp"
#include "sim/pseudorigid/system.hpp"
#include "sim/pseudorigid/system_detail.hpp"

namespace pronk::pseudorigid {

void MechanismSystem::add_block(int row, int col, const Matrix3d& b) const {
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      if (b(i, k) != 0.0) triplets_.emplace_back(row + i, col + k, b(i, k));
    }
  }
}

/// d(force on target)/d(state) for a force depending on the position (kx) and
/// velocity (kv) of `source`.
void MechanismSystem::jac_force(const NodeRef& target, const NodeRef& source, const Matrix3d& kx,
                                const Matrix3d& kv) const {
  std::array<Transfer, 4> tr;
  const int nt = transfers(target, tr);
  int src_mass[4];
  double src_w[4];
  int ns = 0;
  if (source.kind == NodeRef::Kind::kMass) {
    src_mass[0] = source.index;
    src_w[0] = 1.0;
    ns = 1;
  } else if (source.kind == NodeRef::Kind::kGhost) {
    const GhostPoint& g = m_.ghost_points[source.index];
    for (int i = 0; i < 4; ++i) {
      src_mass[i] = m_.bodies[g.body].first_mass + i;
      src_w[i] = g.weights[i];
    }
    ns = 4;
  }
  for (int a = 0; a < nt; ++a) {
    const Matrix3d tx = tr[a].t * kx, tv = tr[a].t * kv;
    for (int b = 0; b < ns; ++b) {
      const int k = src_mass[b];
      add_block(6 * tr[a].mass + 3, 6 * k, src_w[b] * tx);
      add_block(6 * tr[a].mass + 3, 6 * k + 3, (src_w[b] * inv_mass_[k]) * tv);
    }
  }
}

/// d(force on target)/d(x) for a force that changes by d * omega_body of `body`.
void MechanismSystem::jac_rotation(const NodeRef& target, int body, const Matrix3d& d) const {
  std::array<Transfer, 4> tr;
  const int nt = transfers(target, tr);
  const int f = m_.bodies[body].first_mass;
  for (int a = 0; a < nt; ++a) {
    const Matrix3d td = tr[a].t * d;
    for (int k = 0; k < 4; ++k) add_block(6 * tr[a].mass + 3, 6 * (f + k), td * dframes_[body][k]);
  }
}

/// Rotation dependence of the ghost-point transfer itself: F_i = R G_i R^T F.
void MechanismSystem::jac_transfer(const NodeRef& target, const Vector3d& force) const {
  if (target.kind != NodeRef::Kind::kGhost) return;
  if (m_.simulation.ghost_transfer == GhostTransfer::kBarycentric) return;  // constant weights
  const GhostPoint& g = m_.ghost_points[target.index];
  const Matrix3d& r = frames_[g.body].rotation;
  const Vector3d fb = r.transpose() * force;
  const int f = m_.bodies[g.body].first_mass;
  for (int i = 0; i < 4; ++i) {
    const Matrix3d d = r * (g.transfer[i] * skew(fb) - skew(g.transfer[i] * fb));
    for (int k = 0; k < 4; ++k) add_block(6 * (f + i) + 3, 6 * (f + k), d * dframes_[g.body][k]);
  }
}

void MechanismSystem::jacobian(double t, const ode::Vec& y,
                               Eigen::SparseMatrix<double>& jac) const {
  if (any_rigid_) {  // a rigid body's rotation: forward differences of the whole RHS
    ode::difference_jacobian(*this, t, y, jac);
    return;
  }
  update_frames(y, true);
  triplets_.clear();
  const int nm = static_cast<int>(m_.masses.size());
  for (int j = 0; j < nm; ++j) {
    for (int i = 0; i < 3; ++i) triplets_.emplace_back(6 * j + i, 6 * j + 3 + i, inv_mass_[j]);
  }
  for (size_t i = 0; i < m_.connections.size(); ++i) {
    const Connection& c = m_.connections[i];
    const Vector3d d = node_position(c.a, y) - node_position(c.b, y);
    const Vector3d v = node_velocity(c.a, y) - node_velocity(c.b, y);
    const ConnectionForce cf =
        connection_force(c, in_->rest_length[i], d, v, m_.simulation.zero_length_epsilon);
    jac_force(c.a, c.a, cf.d_dx, cf.d_dv);
    jac_force(c.a, c.b, -cf.d_dx, -cf.d_dv);
    jac_force(c.b, c.a, -cf.d_dx, -cf.d_dv);
    jac_force(c.b, c.b, cf.d_dx, cf.d_dv);
    jac_transfer(c.a, cf.force);
    jac_transfer(c.b, -cf.force);
  }
  for (size_t si = 0; si < m_.surfaces.size(); ++si) {
    // (body-attached: attached_surfaces_jacobian, below)
    if (m_.surfaces[si].body < 0) grounded_surface_jacobian(si, y);
  }
  for (int b = 0; b < static_cast<int>(m_.bodies.size()); ++b) attached_surfaces_jacobian(b, y);
  for (const WorldForce& f : m_.world_forces) jac_transfer(f.node, f.force);
  auto body_force_jac = [&](const NodeRef& node, int body, const Vector3d& fb) {
    const Matrix3d& r = frames_[body].rotation;
    jac_rotation(node, body, -r * skew(fb));
    jac_transfer(node, r * fb);
  };
  for (const BodyForce& f : m_.body_forces) {
    if (active(f.t_start, f.t_end)) body_force_jac(f.node, f.body, f.force);
  }
  for (const ImpulseActuator& a : m_.impulse_actuators) {
    if (active(a.t_start, a.t_start + a.duration())) {
      body_force_jac(a.node, a.body, a.force * a.direction);
    }
  }
  const int n = dimension();
  jac.resize(n, n);
  jac.setFromTriplets(triplets_.begin(), triplets_.end());
}

double jacobian_check(const MechanismSystem& sys, double t, const ode::Vec& y, int* worst_row,
                      int* worst_col) {
  const int n = sys.dimension();
  Eigen::SparseMatrix<double> js;
  sys.jacobian(t, y, js);
  const Eigen::MatrixXd ja(js);
  Eigen::MatrixXd jf(n, n);
  ode::Vec yp = y, fp(n), fm(n);
  for (int i = 0; i < n; ++i) {
    const double h = 1e-6 * std::max(1e-3, std::abs(y[i]));
    yp[i] = y[i] + h;
    sys.rhs(t, yp, fp);
    yp[i] = y[i] - h;
    sys.rhs(t, yp, fm);
    yp[i] = y[i];
    jf.col(i) = (fp - fm) / (2.0 * h);
  }
  const double scale = std::max(1.0, ja.cwiseAbs().maxCoeff());
  Eigen::Index r = 0, c = 0;
  const double worst = (ja - jf).cwiseAbs().maxCoeff(&r, &c) / scale;
  if (worst_row) *worst_row = static_cast<int>(r);
  if (worst_col) *worst_col = static_cast<int>(c);
  return worst;
}

}  // namespace pronk::pseudorigid
