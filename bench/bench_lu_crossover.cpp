// Dense vs sparse LU for the stiff solvers' linear systems: where does Eigen's
// SparseLU start to pay? A chain of K pseudo-rigid bodies (four masses each,
// 24 states per body) whose neighbouring masses are joined by springs gives
// mechanism Jacobians of n = 24 K states with the block sparsity of real
// scenes. For each n it times what one RODAS4 step does with the matrix
// E = I/(gamma h) - J: one factorisation and six solves, dense partial-pivoting
// LU vs SparseLU (median of repeats), and prints one JSON document with the
// measured crossover (the smallest n from which sparse wins at every larger n).
// SolverOptions::dense_lu_max_dimension defaults to the crossover found here.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseLU>

#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/system.hpp"

using namespace pronk::pseudorigid;

namespace {

Mechanism chain(int bodies) {
  Mechanism m;
  m.gravity.setZero();
  for (int b = 0; b < bodies; ++b) {
    BodySpec s;
    s.name = "body";
    s.name += std::to_string(b);
    s.mass = 1.5;
    s.inertia = Eigen::Vector3d(0.0074, 0.0106, 0.0164).asDiagonal();
    s.com = Eigen::Vector3d(0.4 * b, 0.0, 0.0);
    s.internal_stiffness = 1e6;
    std::string error;
    add_body(m, s, &error);
  }
  for (int b = 0; b + 1 < bodies; ++b) {
    for (int i = 0; i < 4; ++i) {
      Connection c;
      c.name = "link";
      c.a = NodeRef{NodeRef::Kind::kMass, 4 * b + i};
      c.b = NodeRef{NodeRef::Kind::kMass, 4 * (b + 1) + i};
      c.stiffness = 1e4;
      c.rest_length = 0.4;
      m.connections.push_back(c);
    }
  }
  return m;
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main() {
  const double gamma_h_inv = 1.0 / (0.25 * 1e-3);  // h = 1 ms [1/s]
  std::printf("{\"benchmark\": \"dense vs sparse LU, factorise + 6 solves\",\n  \"rows\": [\n");
  int crossover = -1;
  std::vector<std::pair<int, bool>> sparse_wins;
  bool first = true;
  for (int bodies : {1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 24, 32}) {
    const Mechanism m = chain(bodies);
    const MechanismSystem sys(m);
    const Eigen::VectorXd y = m.initial_state();
    Eigen::SparseMatrix<double> j;
    sys.jacobian(0.0, y, j);
    const int n = static_cast<int>(y.size());
    Eigen::SparseMatrix<double> e = -j;
    for (int i = 0; i < n; ++i) e.coeffRef(i, i) += gamma_h_inv;
    e.makeCompressed();
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
    const int reps = std::max(5, 4000 / n);
    std::vector<double> td, ts;
    Eigen::VectorXd x(n), x_dense(n);
    for (int r = 0; r < 7; ++r) {
      double t0 = now();
      for (int k = 0; k < reps; ++k) {
        Eigen::MatrixXd ed(e);
        Eigen::PartialPivLU<Eigen::MatrixXd> lu(ed);
        x = b;
        for (int s = 0; s < 6; ++s) x = lu.solve(x);
      }
      td.push_back((now() - t0) / reps);
      x_dense = x;
      t0 = now();
      for (int k = 0; k < reps; ++k) {
        Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
        lu.compute(e);
        x = b;
        for (int s = 0; s < 6; ++s) x = lu.solve(x);
      }
      ts.push_back((now() - t0) / reps);
    }
    const double d = median(td), s = median(ts);
    sparse_wins.emplace_back(n, s < d);
    std::printf(
        "%s    {\"bodies\": %d, \"n\": %d, \"nonzeros\": %ld, \"dense_us\": %.3f, "
        "\"sparse_us\": %.3f, \"sparse_over_dense\": %.3f, \"relative_difference\": %.2g}",
        first ? "" : ",\n", bodies, n, static_cast<long>(e.nonZeros()), 1e6 * d, 1e6 * s, s / d,
        (x - x_dense).norm() / x_dense.norm());
    first = false;
    std::fflush(stdout);
  }
  for (size_t i = 0; i < sparse_wins.size(); ++i) {
    bool all = true;
    for (size_t k = i; k < sparse_wins.size(); ++k) all = all && sparse_wins[k].second;
    if (all) {
      crossover = sparse_wins[i].first;
      break;
    }
  }
  std::printf("\n  ],\n  \"crossover_n\": %d\n}\n", crossover);
  return 0;
}
