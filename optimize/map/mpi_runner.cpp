#include "optimize/map/mpi_runner.hpp"

#include <cstdlib>
#include <cstring>

#ifdef PRONK_WITH_MPI
#include <mpi.h>

#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#endif

namespace pronk::optimize::map {

bool mpi_built() {
#ifdef PRONK_WITH_MPI
  return true;
#else
  return false;
#endif
}

bool mpi_launched() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(var);
    if (v && std::atol(v) > 1) return true;
  }
  return false;
}

#ifdef PRONK_WITH_MPI

namespace {

// Every call goes through the PMPI_ entry points (MPI standard, profiling
// interface): Debian's sequential MUMPS, linked in through Ipopt, exports fake
// MPI_Init, MPI_Comm_rank (always 0), MPI_Finalize (no-op) and MPI_Wtime that
// would otherwise shadow OpenMPI's (every rank would be rank 0 and never finalize).

constexpr int kTagReady = 1;   // worker -> root: first request
constexpr int kTagResult = 2;  // worker -> root: "position\n" + result JSON (also a request)
constexpr int kTagTask = 3;    // root -> worker: {position, kind, index, good, bad}
constexpr int kTagStop = 4;    // root -> worker: return from serve()

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI error in ") + what);
}

void pause_briefly() { std::this_thread::sleep_for(std::chrono::microseconds(200)); }

}  // namespace

MpiSession::MpiSession() {
  int provided = 0;
  check(PMPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED)
    throw std::runtime_error("MPI does not provide MPI_THREAD_FUNNELED");
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  PMPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { PMPI_Finalize(); }

MpiRunner::MpiRunner(const MpiSession& session)
    : size_(session.size()), greeted_(static_cast<size_t>(session.size()), false) {}

MpiRunner::~MpiRunner() {
  try {
    release_workers();
  } catch (...) {
  }
}

std::string MpiRunner::describe() const { return std::to_string(size_) + " MPI ranks"; }

void MpiRunner::release_workers() {
  if (released_) return;
  released_ = true;
  for (int w = 1; w < size_; ++w) {
    if (!greeted_[static_cast<size_t>(w)]) {
      int dummy = 0;
      check(PMPI_Recv(&dummy, 1, MPI_INT, w, kTagReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "MPI_Recv");
      greeted_[static_cast<size_t>(w)] = true;
    }
    check(PMPI_Send(nullptr, 0, MPI_INT, w, kTagStop, MPI_COMM_WORLD), "MPI_Send");
  }
}

void MpiRunner::run(const MapStudy& st, const std::vector<MapTask>& tasks,
                    const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
                    const std::atomic<bool>* stop) {
  const long n = static_cast<long>(tasks.size());
  std::atomic<long> next{0};
  std::atomic<bool> failed{false};
  std::mutex mu;
  std::exception_ptr error;
  auto claim = [&]() -> long {
    if ((stop && stop->load()) || failed.load()) return -1;
    const long i = next.fetch_add(1);
    return i < n ? i : -1;
  };
  auto deliver = [&](long i, const nlohmann::json& r) {
    std::lock_guard<std::mutex> lock(mu);
    try {
      if (!failed.load()) on_result(tasks[static_cast<size_t>(i)], r);
    } catch (...) {
      if (!error) error = std::current_exception();
      failed.store(true);
    }
  };
  // Rank 0's own worker: no MPI calls on this thread (MPI_THREAD_FUNNELED).
  std::thread local([&] {
    for (long i = claim(); i >= 0; i = claim())
      deliver(i, compute_task(st, tasks[static_cast<size_t>(i)]));
  });
  long outstanding = 0;
  auto send_task = [&](int worker) {
    const long i = claim();
    if (i < 0) {
      idle_.push_back(worker);
      return;
    }
    const MapTask& t = tasks[static_cast<size_t>(i)];
    const double msg[5] = {static_cast<double>(i), static_cast<double>(t.kind),
                           static_cast<double>(t.index), t.good, t.bad};
    check(PMPI_Send(msg, 5, MPI_DOUBLE, worker, kTagTask, MPI_COMM_WORLD), "MPI_Send");
    ++outstanding;
  };
  std::vector<int> idle;
  idle.swap(idle_);
  for (int w : idle) send_task(w);
  try {
    while (true) {
      const bool exhausted = next.load() >= n || (stop && stop->load()) || failed.load();
      if (exhausted && outstanding == 0) break;
      int flag = 0;
      MPI_Status status;
      check(PMPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
      if (!flag) {
        pause_briefly();
        continue;
      }
      const int src = status.MPI_SOURCE;
      if (status.MPI_TAG == kTagReady) {
        int dummy = 0;
        check(PMPI_Recv(&dummy, 1, MPI_INT, src, kTagReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        greeted_[static_cast<size_t>(src)] = true;
      } else if (status.MPI_TAG == kTagResult) {
        int count = 0;
        PMPI_Get_count(&status, MPI_CHAR, &count);
        std::string buf(static_cast<size_t>(count), '\0');
        check(PMPI_Recv(buf.data(), count, MPI_CHAR, src, kTagResult, MPI_COMM_WORLD,
                        MPI_STATUS_IGNORE),
              "MPI_Recv");
        --outstanding;
        const size_t nl = buf.find('\n');
        const long i = std::atol(buf.substr(0, nl).c_str());
        deliver(i, nlohmann::json::parse(buf.substr(nl + 1)));
      } else {
        throw std::runtime_error("MPI: unexpected message tag " + std::to_string(status.MPI_TAG));
      }
      send_task(src);
    }
  } catch (...) {
    failed.store(true);
    local.join();
    throw;
  }
  local.join();
  if (error) std::rethrow_exception(error);
}

void mpi_serve(const MapStudy& st) {
  int dummy = 0;
  check(PMPI_Send(&dummy, 1, MPI_INT, 0, kTagReady, MPI_COMM_WORLD), "MPI_Send");
  while (true) {
    int flag = 0;
    MPI_Status status;
    check(PMPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
    if (!flag) {
      pause_briefly();
      continue;
    }
    if (status.MPI_TAG == kTagStop) {
      check(PMPI_Recv(nullptr, 0, MPI_INT, 0, kTagStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "MPI_Recv");
      return;
    }
    double msg[5];
    check(PMPI_Recv(msg, 5, MPI_DOUBLE, 0, kTagTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv");
    MapTask t;
    t.kind = static_cast<int>(msg[1]);
    t.index = static_cast<long>(msg[2]);
    t.good = msg[3];
    t.bad = msg[4];
    const std::string out =
        std::to_string(static_cast<long>(msg[0])) + "\n" + compute_task(st, t).dump();
    check(PMPI_Send(out.data(), static_cast<int>(out.size()), MPI_CHAR, 0, kTagResult,
                    MPI_COMM_WORLD),
          "MPI_Send");
  }
}

#endif

}  // namespace pronk::optimize::map
