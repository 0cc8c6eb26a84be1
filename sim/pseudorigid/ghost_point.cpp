#include "sim/pseudorigid/ghost_point.hpp"

#include <Eigen/LU>

#include "sim/pseudorigid/attitude.hpp"

namespace pronk::pseudorigid {

void prepare_ghost_point(const std::array<Eigen::Vector3d, 4>& local, GhostPoint* g) {
  // Barycentric weights: [r_1 .. r_4; 1 1 1 1] w = [r_g; 1].
  Eigen::Matrix4d b;
  for (int i = 0; i < 4; ++i) b.col(i) << local[i], 1.0;
  Eigen::Vector4d rhs;
  rhs << g->local, 1.0;
  g->weights = b.fullPivLu().solve(rhs);
  // Minimum-norm transfer.
  Eigen::Matrix<double, 6, 12> a;
  for (int i = 0; i < 4; ++i) {
    a.block<3, 3>(0, 3 * i) = Eigen::Matrix3d::Identity();
    a.block<3, 3>(3, 3 * i) = skew(local[i]);
  }
  Eigen::Matrix<double, 6, 3> rhs_map;
  rhs_map.topRows<3>() = Eigen::Matrix3d::Identity();
  rhs_map.bottomRows<3>() = skew(g->local);
  const Eigen::Matrix<double, 6, 6> aat = a * a.transpose();
  const Eigen::Matrix<double, 12, 3> gmap = a.transpose() * aat.fullPivLu().solve(rhs_map);
  for (int i = 0; i < 4; ++i) g->transfer[i] = gmap.block<3, 3>(3 * i, 0);
}

}  // namespace pronk::pseudorigid
