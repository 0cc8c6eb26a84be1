// Benchmark of `pronk map` (docs/maps.md, issue 6): a 30 x 30 map with 16 trials per
// cell on the legged pulse model (the seed's controller, duty 10-50 % x initial
// tilt 0-20 deg, 12 s trials, stride-map spectral radius per duty). Prints one
// JSON object of medians over interleaved runs (every configuration once per
// repeat, so a noisy neighbour hits them alike) and the load average:
//
//   threads_1_s, threads_2_s        run_map in this process on 1 and 2 threads
//   pronk_1_thread_s                `pronk map --threads 1`, the whole process (no mpirun)
//   mpirun_1_rank_s, mpirun_2_ranks_s
//                                   `mpirun -np 1|2 pronk map`, the whole job: process
//                                   start-up, MPI_Init (2 ranks only: one rank is a plain
//                                   1-thread run), the map, MPI_Finalize
//   mpi_map_1_rank_s, mpi_map_2_ranks_s
//                                   run_map under the MPI runner only (this executable
//                                   under mpirun, --mpi-child): no start-up, no MPI_Init
//   mpi_init_s                      MPI_Init of rank 0 in the 2-rank runs
//   worker_*                        what rank 1 did in the 2-rank runs (tasks, chunks,
//                                   compute and idle time)
//
// and the speed-ups between them (the acceptance figure of issue 6 is
// mpirun_speedup = mpirun_1_rank_s / mpirun_2_ranks_s). With MPI built the
// pronk executable beside this one is run; its results are compared byte for
// byte with the threaded run's (outputs_identical).
//
//   build/bench_map [repeats=3] [cells_per_axis=30] [trials=16]
//   (internal) mpirun -np N build/bench_map --mpi-child STUDY OUT_DIR
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
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

double seconds(const timeval& t) {
  return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
}

// CPU seconds of this process (all threads) or of its waited-for children.
double cpu_s(int who) {
  rusage u{};
  ::getrusage(who, &u);
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}

// The 1-minute load average: the machine is shared, so timings need their context.
double load_average() {
  double l = 0.0;
  std::ifstream("/proc/loadavg") >> l;
  return l;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
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

#ifdef PRONK_WITH_MPI
// Under mpirun: rank 0 times run_map with the MPI runner and prints one JSON
// line; the other ranks serve and print what they did.
int mpi_child(const std::string& study_path, const std::string& out_dir) {
  const double t0 = now();
  m::MpiSession session;
  const double init = now() - t0;
  const m::MapStudy st = m::load_map_study(study_path, {});
  if (session.rank() != 0) {
    const m::MpiWorkerStats w = m::mpi_serve(st);
    const json line = {{"rank", session.rank()}, {"tasks", w.tasks},
                       {"chunks", w.chunks},     {"compute_s", w.compute_s},
                       {"idle_s", w.idle_s},     {"total_s", w.total_s},
                       {"init_s", init}};
    std::printf("%s\n", line.dump().c_str());
    return 0;
  }
  m::MpiRunner runner(session);
  m::MapRunOptions opt;
  opt.runner = &runner;
  opt.out_dir = out_dir;
  opt.figures = false;
  const double t1 = now();
  const m::MapOutcome o = m::run_map(st, opt);
  const double map = now() - t1;
  runner.release_workers();
  const m::MpiRunStats& s = runner.stats();
  const json line = {{"rank", 0},
                     {"init_s", init},
                     {"map_s", map},
                     {"cells_s", o.cells_time},
                     {"bisection_s", o.bisection_time},
                     {"output_s", o.output_time},
                     {"tasks_local", s.tasks_local},
                     {"tasks_remote", s.tasks_remote},
                     {"chunks", s.chunks},
                     {"largest_chunk", s.largest_chunk}};
  std::printf("%s\n", line.dump().c_str());
  return o.status == "completed" ? 0 : 1;
}
#endif

// Runs a shell command; its wall time, the CPU time of everything it started,
// and the JSON lines it printed.
struct Command {
  double wall = 0.0, cpu = 0.0;
  std::vector<json> lines;
};

Command run_command(const std::string& cmd) {
  Command c;
  const double cpu0 = cpu_s(RUSAGE_CHILDREN), t0 = now();
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) {
    std::fprintf(stderr, "bench_map: cannot run %s\n", cmd.c_str());
    std::exit(1);
  }
  char buf[4096];
  std::string out;
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int rc = ::pclose(p);
  c.wall = now() - t0;
  c.cpu = cpu_s(RUSAGE_CHILDREN) - cpu0;
  if (rc != 0) {
    std::fprintf(stderr, "bench_map: failed (%d): %s\n%s", rc, cmd.c_str(), out.c_str());
    std::exit(1);
  }
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] == '{') c.lines.push_back(json::parse(line));
  return c;
}

// The line of the given rank (or an empty object).
json rank_line(const Command& c, int rank) {
  for (const json& l : c.lines)
    if (l.value("rank", -1) == rank) return l;
  return json::object();
}

bool same_outputs(const std::string& a, const std::string& b) {
  for (const char* f : {"cells.csv", "trials.csv", "boundary.csv", "summary.json"})
    if (slurp(a + "/" + f) != slurp(b + "/" + f)) return false;
  return true;
}

// Wall times and more, per configuration (one entry per repeat).
using Timings = std::map<std::string, std::vector<double>>;

// run_map in this process on 1 and 2 threads; returns the simulations of a map.
long time_threads(const m::MapStudy& st, const std::string& dir, Timings& t) {
  long simulations = 0;
  for (int threads : {1, 2}) {
    m::MapRunOptions opt;
    opt.threads = threads;
    opt.out_dir = dir + "/threads";
    opt.figures = false;
    const double t0 = now(), cpu0 = cpu_s(RUSAGE_SELF);
    const m::MapOutcome o = m::run_map(st, opt);
    const std::string key = "threads_" + std::to_string(threads);
    t[key + "_s"].push_back(now() - t0);
    t[key + "_cpu_s"].push_back(cpu_s(RUSAGE_SELF) - cpu0);
    if (threads == 1) {
      t["threads_1_cells_s"].push_back(o.cells_time);
      t["threads_1_bisection_s"].push_back(o.bisection_time);
      t["threads_1_output_s"].push_back(o.output_time);
    }
    simulations = o.simulations;
  }
  return simulations;
}

// pronk map on one thread, under mpirun on 1 and 2 ranks, and run_map under the MPI
// runner (this executable as --mpi-child, timed inside rank 0).
void time_mpi(const std::string& study_path, const std::string& dir, const std::string& pronk,
              const std::string& self, Timings& t) {
  const std::string mpirun = "mpirun --allow-run-as-root --oversubscribe ";
  const std::string map_args = " map " + study_path + " -q --out " + dir;
  const Command plain = run_command(pronk + map_args + "/plain --threads 1");
  t["pronk_1_thread_s"].push_back(plain.wall);
  for (int ranks : {1, 2}) {
    const std::string np = "-np " + std::to_string(ranks) + " ";
    const std::string key = ranks == 1 ? "1_rank" : "2_ranks";
    // The command of issue 6 (one rank: pronk runs one thread and no MPI at all).
    const Command job = run_command(mpirun + np + pronk + map_args + "/ranks" +
                                    std::to_string(ranks) + (ranks == 1 ? " --threads 1" : ""));
    t["mpirun_" + key + "_s"].push_back(job.wall);
    t["mpirun_" + key + "_cpu_s"].push_back(job.cpu);
    // run_map under the MPI runner, timed inside rank 0.
    const Command child = run_command(mpirun + np + self + " --mpi-child " + study_path + " " +
                                      dir + "/child" + std::to_string(ranks));
    const json r0 = rank_line(child, 0);
    t["mpi_map_" + key + "_s"].push_back(r0.value("map_s", 0.0));
    if (ranks == 2) {
      const json r1 = rank_line(child, 1);
      t["mpi_init_s"].push_back(r0.value("init_s", 0.0));
      t["mpi_map_2_ranks_cells_s"].push_back(r0.value("cells_s", 0.0));
      t["mpi_map_2_ranks_bisection_s"].push_back(r0.value("bisection_s", 0.0));
      t["mpi_map_2_ranks_output_s"].push_back(r0.value("output_s", 0.0));
      t["rank0_tasks"].push_back(r0.value("tasks_local", 0.0));
      t["chunks"].push_back(r0.value("chunks", 0.0));
      t["largest_chunk"].push_back(r0.value("largest_chunk", 0.0));
      t["worker_tasks"].push_back(r1.value("tasks", 0.0));
      t["worker_compute_s"].push_back(r1.value("compute_s", 0.0));
      t["worker_idle_s"].push_back(r1.value("idle_s", 0.0));
      t["worker_total_s"].push_back(r1.value("total_s", 0.0));
    }
  }
}

// The medians, the speedups and the runs of the report.
void add_ratios(Timings& t, bool mpi, const std::string& dir, json& out) {
  for (const auto& [key, v] : t) out[key] = median(v);
  auto ratio = [&](const char* a, const char* b) {
    return t.count(a) && t.count(b) ? median(t[a]) / median(t[b]) : 0.0;
  };
  out["thread_speedup"] = ratio("threads_1_s", "threads_2_s");
  out["threads_1_runs"] = t["threads_1_s"];
  out["threads_2_runs"] = t["threads_2_s"];
  if (mpi) {
    out["mpirun_speedup"] = ratio("mpirun_1_rank_s", "mpirun_2_ranks_s");
    out["mpirun_2_ranks_vs_pronk_1_thread"] = ratio("pronk_1_thread_s", "mpirun_2_ranks_s");
    out["mpi_map_speedup"] = ratio("mpi_map_1_rank_s", "mpi_map_2_ranks_s");
    out["mpi_map_2_ranks_vs_threads_1"] = ratio("threads_1_s", "mpi_map_2_ranks_s");
    out["mpirun_1_rank_runs"] = t["mpirun_1_rank_s"];
    out["mpirun_2_ranks_runs"] = t["mpirun_2_ranks_s"];
    out["mpi_map_1_rank_runs"] = t["mpi_map_1_rank_s"];
    out["mpi_map_2_ranks_runs"] = t["mpi_map_2_ranks_s"];
    out["outputs_identical"] = same_outputs(dir + "/threads", dir + "/ranks2") &&
                               same_outputs(dir + "/threads", dir + "/child2");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::strcmp(argv[1], "--mpi-child") == 0) {
#ifdef PRONK_WITH_MPI
    return mpi_child(argv[2], argv[3]);
#else
    return 2;
#endif
  }
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  const long n = argc > 2 ? std::atol(argv[2]) : 30;
  const long trials = argc > 3 ? std::atol(argv[3]) : 16;
  const std::string dir = "/tmp/pronk_bench_map_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const json doc = bench_study(n, trials);
  const std::string study_path = dir + "/study.json";
  std::ofstream(study_path) << doc.dump(2);
  const m::MapStudy st = m::parse_map_study(doc, study_path, dir);
  const std::string here = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
  const std::string pronk = here + "/pronk", self = here + "/bench_map";
  const bool mpi = m::mpi_built() && std::filesystem::exists(pronk);

  Timings t;
  long simulations = 0;
  const double load_before = load_average();
  for (int r = 0; r < repeats; ++r) {
    simulations = time_threads(st, dir, t);
    if (mpi) time_mpi(study_path, dir, pronk, self, t);
  }
  json out = {{"benchmark", "map"},
              {"cells", st.cells()},
              {"trials_per_cell", trials},
              {"model", "pulse"},
              {"simulations", simulations},
              {"repeats", repeats},
              {"load_average_before", load_before}};
  add_ratios(t, mpi, dir, out);
  out["load_average_after"] = load_average();
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}
