// Peer of `pronk bench`: MuJoCo on an MJCF model equivalent to the quad spring
// hopper drop of `pronk bench` (app/bench/quad_drop.cpp, quad_hopper_mechanism): a
// 1.5 kg body with the seed's inertia (0.0074, 0.0106, 0.0164 kg m^2), four
// prismatic legs with 100 N/m springs of rest length 0.25 m at the hips
// (+-0.14, +-0.115, -0.04) m, 10 g feet, dropped from 0.15 m, no joint damping.
// MuJoCo's soft contact (default solref: time constant 0.02 s, damping ratio 1)
// dissipates at touchdown; that is part of what is measured. Runs each
// integrator (Euler, RK4, implicit) at several time steps for 10 s (2 s with
// --quick): cost per simulated second, energy lost by the first bounce and over
// the run, apex-height error. Prints one JSON document on stdout.
// Usage: pronk_peer_mujoco [--quick] [--repeat N]
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace {

constexpr double kDrop = 0.15;         // foot height above the ground at release [m]
constexpr double kLeg = 0.25;          // leg rest length [m]
constexpr double kFootRadius = 0.005;  // [m]

std::string mjcf(double timestep, const char* integrator) {
  const double z0 = kDrop + kFootRadius + kLeg + 0.04;
  std::string s =
      "<mujoco model='quad_spring_hopper'>\n"
      "  <option timestep='" +
      std::to_string(timestep) + "' integrator='" + integrator +
      "' gravity='0 0 -9.81'><flag energy='enable'/></option>\n"
      "  <worldbody>\n"
      "    <geom name='floor' type='plane' size='5 5 0.1'/>\n"
      "    <body name='body' pos='0 0 " +
      std::to_string(z0) +
      "'>\n"
      "      <freejoint/>\n"
      "      <inertial pos='0 0 0' mass='1.5' diaginertia='0.0074 0.0106 0.0164'/>\n";
  const double hips[4][2] = {{0.14, 0.115}, {0.14, -0.115}, {-0.14, 0.115}, {-0.14, -0.115}};
  for (int i = 0; i < 4; ++i) {
    char b[512];
    std::snprintf(b, sizeof b,
                  "      <body name='foot%d' pos='%g %g -0.04'>\n"
                  "        <joint name='leg%d' type='slide' axis='0 0 1' stiffness='100' "
                  "springref='0' damping='0'/>\n"
                  "        <geom type='sphere' size='%g' pos='0 0 %g' mass='0.01'/>\n"
                  "      </body>\n",
                  i, hips[i][0], hips[i][1], i, kFootRadius, -kLeg);
    s += b;
  }
  s += "    </body>\n  </worldbody>\n</mujoco>\n";
  return s;
}

/// CPU time of the calling thread [s].
double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Result {
  double wall = 0, cpu = 0;  // [s]
  long steps = 0;
  double e0 = 0, first_bounce_loss = 0, total_loss = 0, apex_err = 0;
  std::vector<double> apexes;
  bool finite = true;
};

Result run_once(const std::string& path, double t_end) {
  char err[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, err, sizeof err);
  if (!m) {
    std::fprintf(stderr, "pronk_peer_mujoco: MJCF rejected: %s\n", err);
    std::exit(1);
  }
  mjData* d = mj_makeData(m);
  Result r;
  const long n = std::lround(t_end / m->opt.timestep);
  std::vector<double> z(static_cast<size_t>(n) + 1), e(static_cast<size_t>(n) + 1);
  mj_forward(m, d);
  z[0] = d->qpos[2];
  e[0] = d->energy[0] + d->energy[1];
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu();
  for (long i = 1; i <= n; ++i) {
    mj_step(m, d);
    z[static_cast<size_t>(i)] = d->qpos[2];
    e[static_cast<size_t>(i)] = d->energy[0] + d->energy[1];
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = thread_cpu() - c0;
  r.steps = n;
  double mass = 0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  const double drop_energy = mass * 9.81 * kDrop;
  // Energies are evaluated at the start of a step; the last step's energies come
  // from a final mj_forward.
  mj_forward(m, d);
  e[static_cast<size_t>(n)] = d->energy[0] + d->energy[1];
  r.e0 = e[0];
  r.total_loss = (e[0] - e.back()) / drop_energy;
  for (size_t i = 1; i + 1 < z.size(); ++i) {
    if (!std::isfinite(z[i])) r.finite = false;
    if (z[i] > z[i - 1] && z[i] >= z[i + 1] && z[i] > z[0] - 0.5 * kDrop) {
      const double den = z[i - 1] - 2 * z[i] + z[i + 1];
      const double off = den != 0 ? 0.5 * (z[i - 1] - z[i + 1]) / den : 0.0;
      r.apexes.push_back(z[i] - 0.25 * (z[i - 1] - z[i + 1]) * off);
      if (r.apexes.size() == 1) r.first_bounce_loss = (e[0] - e[i]) / drop_energy;
    }
  }
  for (double a : r.apexes) r.apex_err = std::max(r.apex_err, std::abs(a - z[0]) / kDrop);
  mj_deleteData(d);
  mj_deleteModel(m);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int repeat = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--repeat" && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
      if (repeat < 1 || repeat > 1000) {
        std::fprintf(stderr, "pronk_peer_mujoco: --repeat: expected 1..1000, found %s\n", argv[i]);
        return 2;
      }
    } else {
      std::fprintf(stderr, "usage: pronk_peer_mujoco [--quick] [--repeat N]\n");
      return 2;
    }
  }
  const double t_end = quick ? 2.0 : 10.0;
  nlohmann::json out;
  out["peer"] = "mujoco";
  out["library"] = "MuJoCo " + std::to_string(mj_version());
  out["problem"] =
      "quad spring hopper drop: 1.5 kg body, inertia (0.0074, 0.0106, 0.0164) kg m^2, four "
      "prismatic 100 N/m legs (rest 0.25 m) at (+-0.14, +-0.115, -0.04) m, 10 g feet, 0.15 m "
      "drop, no joint damping, MuJoCo default soft contact";
  out["t_end"] = t_end;
  out["runs"] = nlohmann::json::array();
  char tmpl[] = "/tmp/pronk_mujoco_XXXXXX.xml";
  const std::vector<double> steps =
      quick ? std::vector<double>{1e-3} : std::vector<double>{2e-3, 1e-3, 5e-4, 2.5e-4};
  for (const char* integ : {"Euler", "RK4", "implicit"}) {
    for (double dt : steps) {
      const int fd = mkstemps(tmpl, 4);
      if (fd < 0) {
        std::perror("pronk_peer_mujoco: mkstemps");
        return 1;
      }
      const std::string xml = mjcf(dt, integ);
      if (write(fd, xml.data(), xml.size()) != static_cast<ssize_t>(xml.size())) return 1;
      close(fd);
      std::vector<double> walls, cpus;
      Result r;
      for (int i = 0; i < repeat; ++i) {
        r = run_once(tmpl, t_end);
        walls.push_back(r.wall);
        cpus.push_back(r.cpu);
      }
      unlink(tmpl);
      std::snprintf(tmpl, sizeof tmpl, "/tmp/pronk_mujoco_XXXXXX.xml");
      std::sort(walls.begin(), walls.end());
      std::sort(cpus.begin(), cpus.end());
      const double wall = walls[walls.size() / 2], cpu = cpus[cpus.size() / 2];
      out["runs"].push_back({{"integrator", integ},
                             {"timestep", dt},
                             {"status", r.finite ? "completed" : "diverged"},
                             {"wall_s", wall},
                             {"cpu_s", cpu},
                             {"cost_per_sim_s", cpu / t_end},
                             {"steps", r.steps},
                             {"bounces", r.apexes.size()},
                             {"apex_heights_m", r.apexes},
                             {"apex_height_error_rel", r.apex_err},
                             {"first_bounce_energy_loss_rel", r.first_bounce_loss},
                             {"total_energy_loss_rel", r.total_loss}});
    }
  }
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
