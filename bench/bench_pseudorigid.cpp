// Benchmarks of the pseudo-rigid engine on the seed's satellite (four 1 kg
// masses, six internal springs, 20 s): cost and omega error per solver,
// tolerance and error norm, a stiffness sweep, RODAS4 and RADAU5 vs DOPRI5; plus the
// four-leg drop (studies/mechanisms/four_leg_drop.json): cost and energy-balance
// drift with the barycentric and the minimum-norm ghost transfer.
// Prints one JSON document; wall times are medians of 3 runs.
// `bench_pseudorigid --one K METHOD TOL [state|body] [REPEAT]` runs one satellite setting
// (stiffness K [N/m], rtol = atol = TOL or the fixed step) and prints one JSON line with its
// median thread CPU time.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "io/load/mechanism_loader.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/pseudorigid/simulator.hpp"
#include "sim/pseudorigid/system.hpp"
#include "tests/pseudorigid/scenes.hpp"

using namespace pronk::pseudorigid;
namespace ts = pronk::pseudorigid::test_scenes;

namespace {

/// The run's final body angular velocity against the satellite's analytic precession,
/// relative to the initial spin; -1 when the run kept no state.
double omega_error(const Mechanism& m, const RunSummary& r) {
  if (r.y.empty()) return -1.0;
  const MechanismSystem sys(m);
  return (sys.body_omega(0, r.y.back()) - ts::satellite_omega(r.t.back())).norm() /
         ts::satellite_omega(0).norm();
}

/// One satellite run; `tol` is rtol = atol of the adaptive methods, or the fixed step h [s] of
/// the fixed-step methods (verlet).
void run(const char* group, double k, pronk::ode::Method method, double tol, ErrorNorm norm,
         bool* first) {
  Mechanism m = ts::satellite(k, 20.0);
  m.simulation.solver.method = method;
  m.simulation.solver.rtol = m.simulation.solver.atol = tol;
  if (!pronk::ode::is_adaptive(method)) m.simulation.solver.h_fixed = tol;
  m.simulation.error_norm = norm;
  std::vector<double> walls;
  RunSummary r;
  for (int rep = 0; rep < 3; ++rep) {
    r = simulate(m);
    walls.push_back(r.wall_time);
  }
  std::sort(walls.begin(), walls.end());
  const double err = omega_error(m, r);
  std::printf(
      "%s    {\"group\": \"%s\", \"k\": %g, \"method\": \"%s\", \"tol\": %g, \"norm\": \"%s\", "
      "\"status\": \"%s\", \"wall_s\": %.4g, \"steps\": %ld, \"rejected\": %ld, \"rhs\": %ld, "
      "\"jacobians\": %ld, \"lu\": %ld, \"omega_rel_error\": %.3g, \"max_strain\": %.3g}",
      *first ? "" : ",\n", group, k, std::string(pronk::ode::to_string(method)).c_str(), tol,
      norm == ErrorNorm::kBody ? "body" : "state", std::string(to_string(r.status)).c_str(),
      walls[1], r.counters.steps_accepted, r.counters.steps_rejected, r.counters.rhs_evaluations,
      r.counters.jacobian_evaluations, r.counters.lu_factorizations, err, r.max_strain);
  std::fflush(stdout);
  *first = false;
}

void four_leg(GhostTransfer transfer, double tol, bool* first) {
  const std::string path = std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/four_leg_drop.json";
  nlohmann::json doc = pronk::io::read_json_file(path);
  doc["simulation"]["rtol"] = tol;
  doc["simulation"]["atol"] = tol;
  Mechanism m = pronk::io::parse_mechanism(doc, path).mechanism;
  m.simulation.ghost_transfer = transfer;
  const RunSummary r = simulate(m);
  std::printf(
      "%s    {\"group\": \"four_leg\", \"transfer\": \"%s\", \"tol\": %g, \"t_end\": %g, "
      "\"status\": \"%s\", \"wall_s\": %.4g, \"steps\": %ld, \"rejected\": %ld, \"rhs\": %ld, "
      "\"jacobians\": %ld, \"energy_drift_rel\": %.3g, \"max_strain\": %.3g}",
      *first ? "" : ",\n", transfer == GhostTransfer::kMinNorm ? "min_norm" : "barycentric", tol,
      m.simulation.t_end, std::string(to_string(r.status)).c_str(), r.wall_time,
      r.counters.steps_accepted, r.counters.steps_rejected, r.counters.rhs_evaluations,
      r.counters.jacobian_evaluations, r.energy_drift / r.energy_scale, r.max_strain);
  std::fflush(stdout);
  *first = false;
}

/// CPU time of the calling thread [s].
double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// --one K METHOD TOL [NORM] [REPEAT]: one satellite run, median thread CPU of REPEAT.
int run_one(int argc, char** argv) {
  const double k = std::atof(argv[2]);
  pronk::ode::Method method{};
  if (!pronk::ode::parse_method(argv[3], &method)) {
    std::fprintf(stderr, "bench_pseudorigid: unknown method %s\n", argv[3]);
    return 2;
  }
  const double tol = std::atof(argv[4]);
  const ErrorNorm norm =
      argc > 5 && std::string(argv[5]) == "body" ? ErrorNorm::kBody : ErrorNorm::kState;
  const int repeat = argc > 6 ? std::max(1, std::atoi(argv[6])) : 1;
  Mechanism m = ts::satellite(k, 20.0);
  m.simulation.solver.method = method;
  m.simulation.solver.rtol = m.simulation.solver.atol = tol;
  if (!pronk::ode::is_adaptive(method)) m.simulation.solver.h_fixed = tol;
  m.simulation.error_norm = norm;
  std::vector<double> cpus;
  RunSummary r;
  for (int rep = 0; rep < repeat; ++rep) {
    const double c0 = thread_cpu();
    r = simulate(m);
    cpus.push_back(thread_cpu() - c0);
  }
  std::sort(cpus.begin(), cpus.end());
  const double err = omega_error(m, r);
  std::printf(
      "{\"k\": %g, \"method\": \"%s\", \"tol\": %g, \"norm\": \"%s\", \"status\": \"%s\", "
      "\"cpu_s\": %.4g, \"steps\": %ld, \"rejected\": %ld, \"rhs\": %ld, \"jacobians\": %ld, "
      "\"lu\": %ld, \"omega_rel_error\": %.3g}\n",
      k, argv[3], tol, norm == ErrorNorm::kBody ? "body" : "state",
      std::string(to_string(r.status)).c_str(), cpus[cpus.size() / 2], r.counters.steps_accepted,
      r.counters.steps_rejected, r.counters.rhs_evaluations, r.counters.jacobian_evaluations,
      r.counters.lu_factorizations, err);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using pronk::ode::Method;
  if (argc >= 5 && std::string(argv[1]) == "--one") return run_one(argc, argv);
  bool first = true;
  std::printf("{\"benchmark\": \"pseudorigid satellite, 4 x 1 kg, 20 s\",\n  \"runs\": [\n");
  for (double tol : {1e-4, 1e-6, 1e-8}) {
    run("tolerance", 1e6, Method::kRodas4, tol, ErrorNorm::kState, &first);
    run("tolerance", 1e6, Method::kRodas4, tol, ErrorNorm::kBody, &first);
  }
  for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    run("tolerance_radau5", 1e6, Method::kRadau5, tol, ErrorNorm::kState, &first);
  }
  // Velocity Verlet: "tol" is the fixed step [s]; stable for h < 2 / omega_max (~1e-3 s here).
  for (double h : {8e-4, 5e-4, 2.5e-4, 1e-4}) {
    run("verlet", 1e6, Method::kVerlet, h, ErrorNorm::kState, &first);
  }
  run("explicit", 1e6, Method::kDopri5, 1e-5, ErrorNorm::kState, &first);
  run("explicit", 1e6, Method::kDopri5, 1e-6, ErrorNorm::kState, &first);
  run("explicit", 1e6, Method::kDopri5, 1e-8, ErrorNorm::kState, &first);
  for (double k : {1e4, 1e5, 1e6, 1e7, 1e8}) {
    run("stiffness", k, Method::kRodas4, 1e-6, ErrorNorm::kState, &first);
    run("stiffness_dopri5", k, Method::kDopri5, 1e-6, ErrorNorm::kState, &first);
    run("stiffness_radau5", k, Method::kRadau5, 1e-8, ErrorNorm::kState, &first);
    // Half the stability limit 2 / omega_max, omega_max ~ 2 sqrt(k / m) = 2000 rad/s at 1e6.
    run("stiffness_verlet", k, Method::kVerlet, 5e-4 * std::sqrt(1e6 / k), ErrorNorm::kState,
        &first);
  }
  for (double tol : {1e-6, 1e-8}) {
    four_leg(GhostTransfer::kBarycentric, tol, &first);
    four_leg(GhostTransfer::kMinNorm, tol, &first);
  }
  std::printf("\n  ]\n}\n");
  return 0;
}
