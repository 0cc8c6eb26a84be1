#include "optimize/mpi/task_farm.hpp"

#include <cstdlib>
#include <cstring>

#ifdef PRONK_WITH_MPI
#include <mpi.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <exception>
#include <filesystem>
#include <list>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

#include "io/load/input_error.hpp"
#include "optimize/progress.hpp"
#endif

namespace pronk::optimize::mpi {

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

using nlohmann::json;

// Every call goes through the PMPI_ entry points (MPI standard, profiling
// interface): Debian's sequential MUMPS, linked in through Ipopt, exports fake
// MPI_Init, MPI_Comm_rank (always 0), MPI_Finalize (no-op) and MPI_Wtime that
// would otherwise shadow OpenMPI's (every rank would be rank 0 and never finalize).
//
// The protocol. Rank 0 keeps kChunksInHand chunks at every worker rank; each
// chunk is answered by exactly one message (its results, or the error of the
// task that threw). MPI keeps the messages between two ranks in order, so a
// worker receiving kTagCancel holds exactly the chunks sent before it.
constexpr int kTagTasks = 1;    // root -> worker: a chunk of tasks (doubles)
constexpr int kTagCancel = 2;   // root -> worker: answer the chunks in hand at once (partly done)
constexpr int kTagStop = 3;     // root -> worker: return from mpi_serve()
constexpr int kTagResults = 4;  // worker -> root: a chunk's results, "position json\n" per task
constexpr int kTagError = 5;    // worker -> root: a chunk's task threw: the error as JSON
constexpr int kTagContext = 6;  // root -> worker: a context (text) for the tasks that follow

constexpr int kChunksInHand = 2;    // one computed, one waiting: no idle round trips
constexpr long kGuidedDivisor = 4;  // chunk = max(1, tasks left / (4 x workers))
// A chunk is, per task: its position, the payload's length, the payload.

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI error in ") + what);
}

// Sleeps between polls that found nothing: 50 us, doubling to 1 ms. Waiting in a
// blocking MPI call instead would spin (OpenMPI polls), taking the core of a
// computing rank on a machine with one core per rank. A worker holds its next
// chunk while it computes one (a task is about a millisecond or more), so
// rank 0 answering up to 1 ms late costs nothing.
class Backoff {
 public:
  void reset() { us_ = kMinUs; }
  void sleep() {
    std::this_thread::sleep_for(std::chrono::microseconds(us_));
    us_ = std::min(2 * us_, kMaxUs);
  }

 private:
  static constexpr long kMinUs = 50, kMaxUs = 1000;
  long us_ = kMinUs;
};

// Nonblocking sends, their buffers kept until MPI is done with them: a rank
// goes on computing or dispatching while a large message waits for its receiver.
class PendingSends {
 public:
  PendingSends() = default;
  PendingSends(const PendingSends&) = delete;
  PendingSends& operator=(const PendingSends&) = delete;
  ~PendingSends() {
    try {
      wait_all();
    } catch (...) {
    }
  }
  void doubles(std::vector<double> data, int dest, int tag) {
    Send& s = sends_.emplace_back();
    s.doubles = std::move(data);
    check(PMPI_Isend(s.doubles.data(), static_cast<int>(s.doubles.size()), MPI_DOUBLE, dest, tag,
                     MPI_COMM_WORLD, &s.request),
          "MPI_Isend");
  }
  void text(std::string data, int dest, int tag) {
    Send& s = sends_.emplace_back();
    s.text = std::move(data);
    check(PMPI_Isend(s.text.data(), static_cast<int>(s.text.size()), MPI_CHAR, dest, tag,
                     MPI_COMM_WORLD, &s.request),
          "MPI_Isend");
  }
  /// Frees the buffers of completed sends.
  void progress() {
    for (auto it = sends_.begin(); it != sends_.end();) {
      int done = 0;
      check(PMPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
      it = done ? sends_.erase(it) : std::next(it);
    }
  }
  void wait_all() {
    Backoff backoff;
    for (progress(); !sends_.empty(); progress()) backoff.sleep();
  }

 private:
  struct Send {
    MPI_Request request = MPI_REQUEST_NULL;
    std::vector<double> doubles;
    std::string text;
  };
  std::list<Send> sends_;  // stable addresses
};

// A received message (matched probe: exactly the message probed is received).
struct Message {
  int source = 0, tag = 0;
  std::vector<double> doubles;  // kTagTasks
  std::string text;             // kTagResults, kTagError, kTagContext
};

bool poll_message(int source, Message& m) {
  int flag = 0;
  MPI_Message handle;
  MPI_Status status;
  check(PMPI_Improbe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &handle, &status), "MPI_Improbe");
  if (!flag) return false;
  m.source = status.MPI_SOURCE;
  m.tag = status.MPI_TAG;
  int count = 0;
  if (m.tag == kTagTasks) {
    check(PMPI_Get_count(&status, MPI_DOUBLE, &count), "MPI_Get_count");
    m.doubles.assign(static_cast<size_t>(count), 0.0);
    check(PMPI_Mrecv(m.doubles.data(), count, MPI_DOUBLE, &handle, MPI_STATUS_IGNORE), "MPI_Mrecv");
  } else {
    check(PMPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
    m.text.assign(static_cast<size_t>(count), '\0');
    check(PMPI_Mrecv(m.text.data(), count, MPI_CHAR, &handle, MPI_STATUS_IGNORE), "MPI_Mrecv");
  }
  return true;
}

// The error of a task as text (an io::InputError keeps its parts, so rank 0
// reports it as bad input, exit 2, exactly like a one-process run).
std::string encode_current_error() {
  json j;
  try {
    throw;
  } catch (const io::InputError& e) {
    j = {{"input_error", {e.file(), e.pointer(), e.expected(), e.found()}}};
  } catch (const std::exception& e) {
    j = {{"error", e.what()}};
  } catch (...) {
    j = {{"error", "unknown exception"}};
  }
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::exception_ptr decode_error(int rank, const std::string& text) {
  try {
    const json j = json::parse(text);
    if (j.contains("input_error")) {
      const json& p = j.at("input_error");
      return std::make_exception_ptr(
          io::InputError(p.at(0).get<std::string>(), p.at(1).get<std::string>(),
                         p.at(2).get<std::string>(), p.at(3).get<std::string>()));
    }
    return std::make_exception_ptr(std::runtime_error("MPI rank " + std::to_string(rank) + ": " +
                                                      j.at("error").get<std::string>()));
  } catch (const json::exception&) {
    return std::make_exception_ptr(
        std::runtime_error("MPI rank " + std::to_string(rank) + ": an unreadable error report"));
  }
}

// OpenMPI with every rank on this node, and no point-to-point layer chosen:
// ob1 (shared memory), which it would select anyway after probing the cm layer's
// Omni-Path/libfabric transports for about 0.2 s.
void prefer_shared_memory_on_one_node() {
  const char* world = std::getenv("OMPI_COMM_WORLD_SIZE");
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  if (world && local && std::strcmp(world, local) == 0 && !std::getenv("OMPI_MCA_pml"))
    ::setenv("OMPI_MCA_pml", "ob1", 0);
}

// OpenMPI 4.1's launcher, PMIx 4.2, connects every rank to mpirun (or the
// node's daemon) over loopback TCP without TCP_NODELAY: in MPI_Finalize a small
// message then waits for the delayed ACK of the one before (Nagle), 40 ms on
// Linux, which is 6 % of a 2-rank map of 0.7 s. After MPI_Init this sets
// TCP_NODELAY on this process's TCP connections to a loopback address that lack
// it (only MPI's own: pronk opens no sockets), which makes MPI_Finalize 3 ms.
void no_delayed_acks_to_the_launcher() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    const int fd = std::atoi(entry.path().filename().c_str());
    int type = 0, nodelay = 0;
    socklen_t len = sizeof type;
    if (::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) != 0 || type != SOCK_STREAM) continue;
    sockaddr_storage peer{};
    len = sizeof peer;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &len) != 0) continue;
    bool loopback = false;
    if (peer.ss_family == AF_INET) {
      const auto* a = reinterpret_cast<const sockaddr_in*>(&peer);
      loopback = (ntohl(a->sin_addr.s_addr) >> 24) == 127;
    } else if (peer.ss_family == AF_INET6) {
      const auto* a = reinterpret_cast<const sockaddr_in6*>(&peer);
      loopback = IN6_IS_ADDR_LOOPBACK(&a->sin6_addr);
    }
    len = sizeof nodelay;
    if (!loopback || ::getsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &nodelay, &len) != 0 || nodelay)
      continue;
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  }
}

}  // namespace

MpiSession::MpiSession() {
  prefer_shared_memory_on_one_node();
  int provided = 0;
  check(PMPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED)
    throw std::runtime_error("MPI does not provide MPI_THREAD_FUNNELED");
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  PMPI_Comm_size(MPI_COMM_WORLD, &size_);
  no_delayed_acks_to_the_launcher();
}

MpiSession::~MpiSession() { PMPI_Finalize(); }

TaskFarm::TaskFarm(const MpiSession& session) : size_(session.size()) {}

TaskFarm::~TaskFarm() {
  try {
    release_workers();
  } catch (...) {
  }
}

void TaskFarm::broadcast(const std::string& context) {
  PendingSends sends;
  for (int w = 1; w < size_; ++w) sends.text(context, w, kTagContext);
}

void TaskFarm::release_workers() {
  if (released_) return;
  released_ = true;
  PendingSends sends;
  for (int w = 1; w < size_; ++w) sends.text(std::string(), w, kTagStop);
}

namespace {

/// One TaskFarm::run on rank 0: the claims on the tasks (chunks for worker ranks, single
/// tasks for rank 0's thread), the delivery of results, the chunks in hand per worker.
class FarmRun {
 public:
  FarmRun(const std::vector<std::vector<double>>& tasks, const ResultFn& on_result,
          const std::atomic<bool>* stop, int size, FarmStats& stats)
      : tasks_(tasks),
        n_(static_cast<long>(tasks.size())),
        on_result_(on_result),
        stop_(stop),
        size_(size),
        stats_(stats),
        in_hand_(static_cast<size_t>(size), 0) {}

  bool stopped() const { return (stop_ && stop_->load()) || failed_.load(); }
  void fail() { failed_.store(true); }
  const std::exception_ptr& error() const { return error_; }

  /// The next unclaimed tasks [begin, end): a guided chunk, or one task.
  std::pair<long, long> claim(bool guided) {
    std::lock_guard<std::mutex> lock(claim_mu_);
    if (stopped() || next_ >= n_) return {next_, next_};
    const long k = guided ? std::max(1L, (n_ - next_) / (kGuidedDivisor * size_)) : 1L;
    const long begin = next_;
    next_ = std::min(n_, next_ + k);
    return {begin, next_};
  }
  bool exhausted() {
    std::lock_guard<std::mutex> lock(claim_mu_);
    return next_ >= n_;
  }

  // Results reach on_result one at a time; the first error wins and stops the rest.
  void record_error(std::exception_ptr e) {
    std::lock_guard<std::mutex> lock(deliver_mu_);
    if (!error_) error_ = e;
    failed_.store(true);
  }
  void deliver(long i, const json& r) {
    std::lock_guard<std::mutex> lock(deliver_mu_);
    try {
      if (!failed_.load()) on_result_(i, r);
    } catch (...) {
      if (!error_) error_ = std::current_exception();
      failed_.store(true);
    }
  }

  /// Sends worker w a chunk; false when no task is left to claim.
  bool send_chunk(int w) {
    const auto [begin, end] = claim(true);
    if (begin == end) return false;
    std::vector<double> msg;
    for (long i = begin; i < end; ++i) {
      const std::vector<double>& t = tasks_[static_cast<size_t>(i)];
      msg.push_back(static_cast<double>(i));
      msg.push_back(static_cast<double>(t.size()));
      msg.insert(msg.end(), t.begin(), t.end());
    }
    sends_.doubles(std::move(msg), w, kTagTasks);
    ++in_hand_[static_cast<size_t>(w)];
    ++outstanding_;
    ++stats_.chunks;
    stats_.largest_chunk = std::max(stats_.largest_chunk, end - begin);
    return true;
  }

  /// Rank 0's own worker: no MPI calls on this thread (MPI_THREAD_FUNNELED).
  void compute_locally(const ComputeFn& compute) {
    while (true) {
      const auto [i, end] = claim(false);
      if (i == end) break;
      try {
        deliver(i, compute(tasks_[static_cast<size_t>(i)]));
        ++local_tasks_;
      } catch (...) {
        record_error(std::current_exception());
      }
    }
  }
  long local_tasks() const { return local_tasks_.load(); }

  /// Rank 0's MPI loop: answers, new chunks, the cancel on a stop, until none is in hand.
  void serve_workers() {
    bool cancelled = false;
    Backoff backoff;
    Message m;
    while (true) {
      if (stopped() && !cancelled) {
        for (int w = 1; w < size_; ++w)
          if (in_hand_[static_cast<size_t>(w)] > 0) sends_.text(std::string(), w, kTagCancel);
        cancelled = true;
      }
      if (outstanding_ == 0 && (cancelled || exhausted())) break;
      if (!poll_message(MPI_ANY_SOURCE, m)) {
        sends_.progress();
        backoff.sleep();
        continue;
      }
      backoff.reset();
      if (m.tag == kTagResults) {
        deliver_results(m);
      } else if (m.tag == kTagError) {
        record_error(decode_error(m.source, m.text));
      } else {
        throw std::runtime_error("MPI: unexpected message tag " + std::to_string(m.tag));
      }
      --in_hand_[static_cast<size_t>(m.source)];
      --outstanding_;
      while (!cancelled && in_hand_[static_cast<size_t>(m.source)] < kChunksInHand &&
             send_chunk(m.source)) {
      }
    }
    sends_.wait_all();
  }

 private:
  /// Lines "position json\n"; a cancelled chunk's answer may be short or empty.
  void deliver_results(const Message& m) {
    try {
      for (size_t at = 0; at < m.text.size();) {
        const size_t space = m.text.find(' ', at), nl = m.text.find('\n', at);
        const long i = std::strtol(m.text.c_str() + at, nullptr, 10);
        if (space == std::string::npos || nl == std::string::npos || space > nl || i < 0 || i >= n_)
          throw std::runtime_error("a malformed result");
        deliver(i, json::parse(m.text.begin() + static_cast<std::ptrdiff_t>(space + 1),
                               m.text.begin() + static_cast<std::ptrdiff_t>(nl)));
        ++stats_.tasks_remote;
        at = nl + 1;
      }
    } catch (const std::exception& e) {
      record_error(std::make_exception_ptr(std::runtime_error(
          "MPI: the results of rank " + std::to_string(m.source) + ": " + e.what())));
    }
  }

  const std::vector<std::vector<double>>& tasks_;
  const long n_;
  const ResultFn& on_result_;
  const std::atomic<bool>* stop_;
  const int size_;
  FarmStats& stats_;
  std::atomic<bool> failed_{false};
  std::mutex claim_mu_;
  long next_ = 0;
  std::mutex deliver_mu_;
  std::exception_ptr error_;
  PendingSends sends_;
  std::vector<int> in_hand_;
  long outstanding_ = 0;
  std::atomic<long> local_tasks_{0};
};

}  // namespace

void TaskFarm::run(const std::vector<std::vector<double>>& tasks, const ComputeFn& compute,
                   const ResultFn& on_result, const std::atomic<bool>* stop) {
  FarmRun farm(tasks, on_result, stop, size_, stats_);
  // The workers' first chunks go out before rank 0's thread starts claiming.
  for (int c = 0; c < kChunksInHand; ++c)
    for (int w = 1; w < size_; ++w) farm.send_chunk(w);
  std::thread local([&] { farm.compute_locally(compute); });
  try {
    farm.serve_workers();
  } catch (...) {
    farm.fail();
    local.join();
    throw;
  }
  local.join();
  stats_.tasks_local += farm.local_tasks();
  if (farm.error()) std::rethrow_exception(farm.error());
}

WorkerStats serve(const ComputeFn& compute, const ContextFn& on_context) {
  WorkerStats stats;
  const double t0 = monotonic_seconds();
  std::deque<std::vector<double>> chunks;  // in hand, in the order received
  bool cancel = false, released = false;
  PendingSends sends;
  Message m;
  // Takes one message from rank 0, if one is waiting.
  auto receive = [&] {
    if (!poll_message(0, m)) return false;
    if (m.tag == kTagTasks)
      chunks.push_back(std::move(m.doubles));
    else if (m.tag == kTagContext) {
      ++stats.contexts;
      if (on_context) on_context(m.text);
    } else if (m.tag == kTagCancel)
      cancel = true;
    else if (m.tag == kTagStop)
      released = true;
    else
      throw std::runtime_error("MPI: unexpected message tag " + std::to_string(m.tag));
    return true;
  };
  Backoff backoff;
  while (!released) {
    if (chunks.empty()) {
      const double w0 = monotonic_seconds();
      if (receive()) {
        backoff.reset();
      } else {
        sends.progress();
        backoff.sleep();
      }
      cancel = false;  // a cancel that found nothing in hand (its chunks were answered already)
      stats.idle_s += monotonic_seconds() - w0;
      continue;
    }
    const std::vector<double> chunk = std::move(chunks.front());
    chunks.pop_front();
    std::string out;
    int tag = kTagResults;
    for (size_t k = 0; k + 2 <= chunk.size();) {
      // Between tasks: the next chunk or a cancel (nothing after a cancel: those
      // messages belong to the next run).
      while (!cancel && !released && receive()) {
      }
      if (cancel || released) break;
      const long position = static_cast<long>(chunk[k]);
      const size_t length = static_cast<size_t>(chunk[k + 1]);
      if (k + 2 + length > chunk.size()) throw std::runtime_error("MPI: a malformed chunk");
      const std::vector<double> task(chunk.begin() + static_cast<std::ptrdiff_t>(k + 2),
                                     chunk.begin() + static_cast<std::ptrdiff_t>(k + 2 + length));
      k += 2 + length;
      const double c0 = monotonic_seconds();
      try {
        const json r = compute(task);
        out += std::to_string(position) + " " + r.dump() + "\n";
        ++stats.tasks;
      } catch (...) {
        out = encode_current_error();
        tag = kTagError;
      }
      stats.compute_s += monotonic_seconds() - c0;
      if (tag == kTagError) break;
    }
    if (released) break;
    sends.text(std::move(out), 0, tag);
    ++stats.chunks;
    if (cancel) {
      for (size_t c = 0; c < chunks.size(); ++c) sends.text(std::string(), 0, kTagResults);
      chunks.clear();
      cancel = false;
    }
    sends.progress();
  }
  sends.wait_all();
  stats.total_s = monotonic_seconds() - t0;
  return stats;
}

#endif

}  // namespace pronk::optimize::mpi
