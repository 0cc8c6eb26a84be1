// Benchmark of `pronk map` (SPEC 6, issue 6): a 30 x 30 map with 16 trials per
// cell on the legged pulse model (the seed's controller, duty 10-50 % x initial
// tilt 0-20 deg, 12 s trials, stride-map spectral radius per duty). Prints one
// JSON object: median wall times on 1 and 2 threads (interleaved runs) and the
// speed-up; with MPI built, the same on 1 and 2 ranks (mpirun of the pronk
// executable beside this one).
//
//   build/bench_map [repeats=3] [cells_per_axis=30] [trials=16]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "optimize/map/map_runner.hpp"
#include "optimize/map/mpi_runner.hpp"

namespace m = pronk::optimize::map;
using nlohmann::json;

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU seconds of this process (all threads).
double cpu_s() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The 1-minute load average: the machine is shared, so timings need their context.
double load_average() {
  double l = 0.0;
  std::ifstream("/proc/loadavg") >> l;
  return l;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

json bench_study(long cells_per_axis, long trials) {
  json doc =
      json::parse(std::ifstream(std::string(PRONK_SOURCE_DIR) + "/studies/map_seed_duty.json"));
  doc["name"] = "bench_map";
  doc["scene"] = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case3_legged_pulse.json";
  doc["models"] = {"pulse"};
  doc["axes"][0]["count"] = cells_per_axis;
  doc["axes"][1]["count"] = cells_per_axis;
  doc["trials"]["count"] = trials;
  return doc;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  const long n = argc > 2 ? std::atol(argv[2]) : 30;
  const long trials = argc > 3 ? std::atol(argv[3]) : 16;
  const std::string dir = "/tmp/pronk_bench_map_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const json doc = bench_study(n, trials);
  const std::string study_path = dir + "/study.json";
  std::ofstream(study_path) << doc.dump(2);
  const m::MapStudy st = m::parse_map_study(doc, study_path, dir);

  std::vector<double> t1, t2, c1, c2, phase_cells, phase_bisect, phase_out;
  long simulations = 0;
  const double load_before = load_average();
  for (int r = 0; r < repeats; ++r) {
    for (int threads : {1, 2}) {
      m::MapRunOptions opt;
      opt.threads = threads;
      opt.out_dir = dir + "/threads";
      opt.figures = false;
      const double t0 = now(), cpu0 = cpu_s();
      const m::MapOutcome o = m::run_map(st, opt);
      (threads == 1 ? t1 : t2).push_back(now() - t0);
      (threads == 1 ? c1 : c2).push_back(cpu_s() - cpu0);
      if (threads == 1) {
        phase_cells.push_back(o.cells_time);
        phase_bisect.push_back(o.bisection_time);
        phase_out.push_back(o.output_time);
      }
      simulations = o.simulations;
    }
  }
  json out = {{"benchmark", "map"},
              {"cells", st.cells()},
              {"trials_per_cell", trials},
              {"model", "pulse"},
              {"simulations", simulations},
              {"repeats", repeats},
              {"threads_1_s", median(t1)},
              {"threads_2_s", median(t2)},
              {"thread_speedup", median(t1) / median(t2)},
              {"threads_1_runs", t1},
              {"threads_2_runs", t2},
              {"threads_1_cpu_s", median(c1)},
              {"threads_2_cpu_s", median(c2)},
              {"threads_1_cells_s", median(phase_cells)},
              {"threads_1_bisection_s", median(phase_bisect)},
              {"threads_1_output_s", median(phase_out)},
              {"load_average_before", load_before}};
  if (m::mpi_built()) {
    // The pronk executable beside this benchmark, under mpirun (wall time of the whole process).
    const std::string exe =
        std::filesystem::read_symlink("/proc/self/exe").parent_path().string() + "/pronk";
    std::vector<double> r1, r2;
    for (int r = 0; r < repeats; ++r) {
      for (int ranks : {1, 2}) {
        const std::string cmd = "mpirun --allow-run-as-root --oversubscribe -np " +
                                std::to_string(ranks) + " " + exe + " map " + study_path +
                                " -q --threads 1 --out " + dir + "/ranks >/dev/null 2>&1";
        const double t0 = now();
        const int rc = std::system(cmd.c_str());
        const double t = now() - t0;
        if (rc != 0) {
          std::fprintf(stderr, "bench_map: mpirun failed (%d)\n", rc);
          return 1;
        }
        (ranks == 1 ? r1 : r2).push_back(t);
      }
    }
    out["ranks_1_s"] = median(r1);
    out["ranks_2_s"] = median(r2);
    out["rank_speedup"] = median(r1) / median(r2);
    out["ranks_1_runs"] = r1;
    out["ranks_2_runs"] = r2;
  }
  out["load_average_after"] = load_average();
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
