// Peer of `pronk bench`: SUNDIALS CVODE 6 (BDF, Newton) integrating pronk's own
// MechanismSystem right-hand side on the seed's satellite (Ridgely 2001, §4.4.1: four
// 1 kg masses, six internal springs, 20 s), with the linear solver fed three
// ways: dense LU with pronk's analytic Jacobian, sparse KLU with the same
// Jacobian (when SUNDIALS was built with KLU), and dense LU with CVODE's own
// difference-quotient Jacobian (the setting of the issue-3 anchor). Reports,
// per tolerance and per internal stiffness 1e4..1e8 N/m: median wall time,
// steps, RHS / Jacobian / LU counts and the omega error against the analytic
// precession. With --mechanism FILE --drop H it also integrates that mechanism
// (pronk bench passes its quad spring hopper drop) with the dense analytic
// variant per tolerance, sampling every output_interval of the scene: energy
// drift relative to the drop energy M g H, the first bounce's energy change and
// the body's apex heights, the same figures pronk's own run reports.
// Prints one JSON document on stdout.
// Usage: pronk_peer_cvode [--quick] [--repeat N] [--mechanism FILE --drop H]
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#ifdef PRONK_CVODE_KLU
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/ode/sundials_jacobian.hpp"
#include "sim/pseudorigid/system.hpp"
#include "tests/pseudorigid/scenes.hpp"

namespace pr = pronk::pseudorigid;

namespace {

enum class Variant { kDenseAnalytic, kSparseAnalytic, kDenseDifferenceQuotient };

const char* name(Variant v) {
  switch (v) {
    case Variant::kDenseAnalytic:
      return "dense_analytic";
    case Variant::kSparseAnalytic:
      return "sparse_klu_analytic";
    case Variant::kDenseDifferenceQuotient:
      return "dense_dq";
  }
  return "?";
}

/// What the CVODE callbacks need: pronk's system and scratch vectors.
struct UserData {
  const pr::MechanismSystem* sys;
  Eigen::VectorXd y, dydt;
  Eigen::SparseMatrix<double> J;
  /// The N_Vector carries one more component after the mechanism's state: the
  /// energy that has left through dampers and friction minus the work done by
  /// actuators [J], integrated with the state (its Jacobian row is left zero).
  bool balance = false;
  pronk::ode::sundials::SparsePattern pattern;  ///< sparse variant: the Jacobians' pattern
  SUNLinearSolver ls = nullptr;                 ///< sparse variant: KLU
};

int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* u = static_cast<UserData*>(user);
  const long n = u->y.size();
  std::memcpy(u->y.data(), N_VGetArrayPointer(y), sizeof(double) * n);
  u->sys->rhs(t, u->y, u->dydt);
  if (!u->dydt.allFinite()) return 1;  // recoverable: CVODE cuts the step
  std::memcpy(N_VGetArrayPointer(ydot), u->dydt.data(), sizeof(double) * n);
  if (u->balance) {
    const pr::PowerFlows p = u->sys->power(u->y);
    N_VGetArrayPointer(ydot)[n] = p.dissipated - p.actuator;
  }
  return 0;
}

int jac_dense(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector,
              N_Vector) {
  auto* u = static_cast<UserData*>(user);
  std::memcpy(u->y.data(), N_VGetArrayPointer(y), sizeof(double) * u->y.size());
  u->sys->jacobian(t, u->y, u->J);
  pronk::ode::sundials::copy_dense(u->J, J);
  return 0;
}

#ifdef PRONK_CVODE_KLU
/// pronk's sparse Jacobian on the pattern pronk's cvode_bdf uses (the union of the patterns
/// seen and the diagonal, so CVODE forms I - gamma J in place); KLU re-analyses when it grows.
int jac_sparse(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector,
               N_Vector) {
  using Copy = pronk::ode::sundials::SparsePattern::Copy;
  auto* u = static_cast<UserData*>(user);
  std::memcpy(u->y.data(), N_VGetArrayPointer(y), sizeof(double) * u->y.size());
  u->sys->jacobian(t, u->y, u->J);
  const Copy c = u->pattern.copy(u->J, J);
  if (c == Copy::kFailed) return -1;
  if (c == Copy::kGrown) {
    return SUNLinSol_KLUReInit(u->ls, J, u->pattern.nonzeros(), SUNKLU_REINIT_PARTIAL) == 0 ? 0
                                                                                            : -1;
  }
  return 0;
}
#endif

/// CPU time of the calling thread [s].
double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Result {
  bool ok = false;
  std::string status;
  double wall = 0, cpu = 0;  // [s]
  long steps = 0, rhs = 0, rhs_dq = 0, jacobians = 0, lu = 0, error_test_fails = 0;
  double omega_final = 0;
};

/// One CVODE run of the satellite at stiffness k to t_end [s].
Result run_once(double k, double t_end, double tol, Variant v) {
  const pr::Mechanism m = pr::test_scenes::satellite(k, t_end);
  const pr::MechanismSystem sys(m);
  const int n = sys.dimension();
  UserData u{&sys, Eigen::VectorXd(n), Eigen::VectorXd(n), {}, false, {}, nullptr};
  Result r;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu();
  SUNContext ctx = nullptr;
  SUNContext_Create(nullptr, &ctx);
  N_Vector y = N_VNew_Serial(n, ctx);
  const Eigen::VectorXd y0 = m.initial_state();
  std::memcpy(N_VGetArrayPointer(y), y0.data(), sizeof(double) * n);
  void* mem = CVodeCreate(CV_BDF, ctx);
  CVodeInit(mem, rhs, 0.0, y);
  CVodeSStolerances(mem, tol, tol);
  CVodeSetUserData(mem, &u);
  CVodeSetMaxNumSteps(mem, 100000000);
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  if (v == Variant::kSparseAnalytic) {
#ifdef PRONK_CVODE_KLU
    sys.jacobian(0.0, y0, u.J);
    A = SUNSparseMatrix(n, n, u.J.nonZeros() + n, CSC_MAT, ctx);
    LS = SUNLinSol_KLU(y, A, ctx);
    u.ls = LS;
    CVodeSetLinearSolver(mem, LS, A);
    CVodeSetJacFn(mem, jac_sparse);
#endif
  } else {
    A = SUNDenseMatrix(n, n, ctx);
    LS = SUNLinSol_Dense(y, A, ctx);
    CVodeSetLinearSolver(mem, LS, A);
    if (v == Variant::kDenseAnalytic) CVodeSetJacFn(mem, jac_dense);
  }
  sunrealtype t = 0.0;
  const int flag = CVode(mem, t_end, y, &t, CV_NORMAL);
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = thread_cpu() - c0;
  r.ok = flag >= 0;
  r.status = r.ok ? "completed" : "failed: CVode flag " + std::to_string(flag);
  CVodeGetNumSteps(mem, &r.steps);
  CVodeGetNumRhsEvals(mem, &r.rhs);
  CVodeGetNumLinRhsEvals(mem, &r.rhs_dq);
  CVodeGetNumJacEvals(mem, &r.jacobians);
  CVodeGetNumLinSolvSetups(mem, &r.lu);
  CVodeGetNumErrTestFails(mem, &r.error_test_fails);
  if (r.ok) {
    Eigen::VectorXd yf(n);
    std::memcpy(yf.data(), N_VGetArrayPointer(y), sizeof(double) * n);
    r.omega_final = (sys.body_omega(0, yf) - pr::test_scenes::satellite_omega(t)).norm() /
                    pr::test_scenes::satellite_omega(0.0).norm();
  }
  CVodeFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  return r;
}

nlohmann::json run(double k, double t_end, double tol, Variant v, int repeat) {
  std::vector<double> walls, cpus;
  Result r;
  for (int i = 0; i < repeat; ++i) {
    r = run_once(k, t_end, tol, v);
    walls.push_back(r.wall);
    cpus.push_back(r.cpu);
    if (!r.ok) break;
  }
  std::sort(walls.begin(), walls.end());
  std::sort(cpus.begin(), cpus.end());
  nlohmann::json j = {{"variant", name(v)},
                      {"stiffness", k},
                      {"tol", tol},
                      {"t_end", t_end},
                      {"status", r.status},
                      {"wall_s", walls[walls.size() / 2]},
                      {"cpu_s", cpus[cpus.size() / 2]},
                      {"steps", r.steps},
                      {"rhs", r.rhs + r.rhs_dq},
                      {"rhs_for_dq_jacobian", r.rhs_dq},
                      {"jacobians", r.jacobians},
                      {"lu", r.lu},
                      {"error_test_failures", r.error_test_fails}};
  if (r.ok) j["omega_final"] = r.omega_final;
  return j;
}

/// CVODE (BDF, dense LU, pronk's analytic Jacobian) on a mechanism m to its t_end,
/// sampled every output_interval: energy drift and body apexes (drop of height
/// `drop` [m] from rest). The energy error is the energy-balance drift
/// |E + dissipated - work - E0|, the dissipated energy integrated by CVODE as an
/// extra state component.
nlohmann::json run_mechanism(const pr::Mechanism& m, double tol, double drop) {
  const pr::MechanismSystem sys(m);
  const int n = sys.dimension();
  UserData u{&sys, Eigen::VectorXd(n), Eigen::VectorXd(n), {}, true, {}, nullptr};
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu();
  SUNContext ctx = nullptr;
  SUNContext_Create(nullptr, &ctx);
  N_Vector y = N_VNew_Serial(n + 1, ctx);
  const Eigen::VectorXd y0 = m.initial_state();
  std::memcpy(N_VGetArrayPointer(y), y0.data(), sizeof(double) * n);
  N_VGetArrayPointer(y)[n] = 0.0;
  void* mem = CVodeCreate(CV_BDF, ctx);
  CVodeInit(mem, rhs, 0.0, y);
  CVodeSStolerances(mem, tol, tol);
  CVodeSetUserData(mem, &u);
  CVodeSetMaxNumSteps(mem, 100000000);
  SUNMatrix A = SUNDenseMatrix(n + 1, n + 1, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(y, A, ctx);
  CVodeSetLinearSolver(mem, LS, A);
  CVodeSetJacFn(mem, jac_dense);
  const double t_end = m.simulation.t_end, dt = m.simulation.output_interval;
  const double e0 = sys.energies(y0).total();
  std::vector<double> z = {sys.frames(y0)[0].com.z()}, e = {e0};
  double drift = 0.0;
  std::string status = "completed";
  Eigen::VectorXd yi(n);
  for (int i = 1; i * dt <= t_end * (1.0 + 1e-12); ++i) {
    sunrealtype t = 0.0;
    const int flag = CVode(mem, i * dt, y, &t, CV_NORMAL);
    if (flag < 0) {
      status = "failed: CVode flag " + std::to_string(flag);
      break;
    }
    std::memcpy(yi.data(), N_VGetArrayPointer(y), sizeof(double) * n);
    z.push_back(sys.frames(yi)[0].com.z());
    e.push_back(sys.energies(yi).total());
    drift = std::max(drift, std::abs(e.back() + N_VGetArrayPointer(y)[n] - e0));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = thread_cpu() - c0;
  long steps = 0, nrhs = 0, njac = 0, nlu = 0;
  CVodeGetNumSteps(mem, &steps);
  CVodeGetNumRhsEvals(mem, &nrhs);
  CVodeGetNumJacEvals(mem, &njac);
  CVodeGetNumLinSolvSetups(mem, &nlu);
  CVodeFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  // Apexes: local maxima of the body's height above half the drop (foot vibration
  // makes tiny wiggles), refined by a parabola through three samples, as pronk's run.
  const double drop_energy = m.total_mass() * 9.81 * drop;
  std::vector<double> apex;
  double first_loss = 0.0, apex_err = 0.0;
  for (size_t i = 1; i + 1 < z.size(); ++i) {
    if (!(z[i] > z[i - 1] && z[i] >= z[i + 1])) continue;
    const double den = z[i - 1] - 2 * z[i] + z[i + 1];
    const double off = den != 0 ? 0.5 * (z[i - 1] - z[i + 1]) / den : 0.0;
    const double h = z[i] - 0.25 * (z[i - 1] - z[i + 1]) * off;
    if (h <= z.front() - 0.5 * drop) continue;
    if (apex.empty()) first_loss = (e0 - e[i]) / drop_energy;
    apex.push_back(h);
    apex_err = std::max(apex_err, std::abs(h - z.front()) / drop);
  }
  return {{"variant", "dense_analytic"},
          {"tol", tol},
          {"t_end", t_end},
          {"status", status},
          {"wall_s", wall},
          {"cpu_s", cpu},
          {"cost_per_sim_s", cpu / t_end},
          {"steps", steps},
          {"rhs", nrhs},
          {"jacobians", njac},
          {"lu", nlu},
          {"energy_error_rel", drift / drop_energy},
          {"first_bounce_energy_loss_rel", first_loss},
          {"apex_height_error_rel", apex_err},
          {"bounces", apex.size()}};
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int repeat = 3;
  std::string mechanism_file;
  double drop = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--repeat" && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
      if (repeat < 1 || repeat > 1000) {
        std::fprintf(stderr, "pronk_peer_cvode: --repeat: expected 1..1000, found %s\n", argv[i]);
        return 2;
      }
    } else if (a == "--mechanism" && i + 1 < argc) {
      mechanism_file = argv[++i];
    } else if (a == "--drop" && i + 1 < argc) {
      drop = std::atof(argv[++i]);
      if (!(drop > 0.0)) {
        std::fprintf(stderr, "pronk_peer_cvode: --drop: expected a height > 0 m, found %s\n",
                     argv[i]);
        return 2;
      }
    } else {
      std::fprintf(stderr,
                   "usage: pronk_peer_cvode [--quick] [--repeat N] [--mechanism FILE --drop H]\n");
      return 2;
    }
  }
  std::vector<Variant> variants = {Variant::kDenseAnalytic, Variant::kDenseDifferenceQuotient};
#ifdef PRONK_CVODE_KLU
  variants.insert(variants.begin() + 1, Variant::kSparseAnalytic);
#endif
  nlohmann::json out;
  out["peer"] = "cvode";
  out["library"] = std::string("SUNDIALS CVODE ") + SUNDIALS_VERSION;
  out["method"] = "BDF (orders 1-5), Newton iteration, rtol = atol = tol";
  out["problem"] = "pronk satellite (pseudorigid::MechanismSystem RHS and Jacobian), 20 s";
  out["satellite"] = nlohmann::json::array();
  const std::vector<double> tols =
      quick ? std::vector<double>{1e-7} : std::vector<double>{1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
  for (double tol : tols) {
    for (Variant v : variants) out["satellite"].push_back(run(1e6, 20.0, tol, v, repeat));
  }
  out["stiffness"] = nlohmann::json::array();
  const std::vector<double> ks =
      quick ? std::vector<double>{1e4, 1e6} : std::vector<double>{1e4, 1e5, 1e6, 1e7, 1e8};
  for (double k : ks) {
    out["stiffness"].push_back(run(k, 20.0, 1e-6, Variant::kDenseAnalytic, repeat));
  }
  if (!mechanism_file.empty()) {
    if (!(drop > 0.0)) {
      std::fprintf(stderr, "pronk_peer_cvode: --mechanism needs --drop H [m]\n");
      return 2;
    }
    try {
      const pr::Mechanism m =
          pronk::io::parse_mechanism(pronk::io::read_json_file(mechanism_file), mechanism_file)
              .mechanism;
      out["quad_hopper"] = nlohmann::json::array();
      const std::vector<double> qt =
          quick ? std::vector<double>{1e-5} : std::vector<double>{1e-4, 1e-5, 1e-6};
      for (double tol : qt) out["quad_hopper"].push_back(run_mechanism(m, tol, drop));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pronk_peer_cvode: %s\n", e.what());
      return 2;
    }
  }
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
