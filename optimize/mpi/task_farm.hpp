// Independent tasks spread over MPI ranks (optional: built when CMake finds MPI,
// which defines PRONK_WITH_MPI). Used by `pronk map` (a map's cells and row
// bisections) and `pronk optimize` (an evaluation's scenario runs).
//
// Rank 0 owns the outputs; it computes tasks itself on a second thread and hands
// the others out to ranks 1..N-1 in guided chunks (several tasks per message, the
// chunk shrinking with the work left: max(1, left / (4 N)); dynamic load
// balancing, since tasks differ in cost). Every worker rank holds two chunks (it
// computes one while the next waits), so it never idles for a round trip, and
// answers each chunk with one message of its results. A task is a vector of
// doubles; a result is JSON text (doubles exact), so the outputs are
// bit-identical to a one-process run. Rank 0 may also broadcast a context (text)
// that every worker receives before any later task, e.g. the configuration the
// next tasks refer to. Nobody busy-waits: idle ranks poll with sleeps of 50 us
// growing to 1 ms (a blocking MPI receive spins a core that a computing rank needs).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::optimize::mpi {

/// True when this build has MPI.
bool mpi_built();

/// True when the process was started by mpirun/mpiexec with more than one rank
/// (OpenMPI, MPICH/Hydra or PMIx environment variables).
bool mpi_launched();

/// Computes one task (any rank, any thread of rank 0's).
using ComputeFn = std::function<nlohmann::json(const std::vector<double>& task)>;
/// Receives task `index`'s result on rank 0, never concurrently.
using ResultFn = std::function<void(long index, const nlohmann::json& result)>;
/// Receives a context broadcast by rank 0 (worker ranks).
using ContextFn = std::function<void(const std::string& context)>;

#ifdef PRONK_WITH_MPI

/// MPI_Init_thread (funneled) / MPI_Finalize around a scope. When OpenMPI runs
/// every rank on this node and nobody chose a point-to-point layer
/// (OMPI_MCA_pml unset, e.g. by `mpirun --mca pml ...`), it sets
/// OMPI_MCA_pml=ob1 first: shared memory, the layer OpenMPI would pick on one
/// node anyway, without 0.2 s of MPI_Init probing for Omni-Path and
/// libfabric network hardware.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

/// What rank 0 did (summed over its runs).
struct FarmStats {
  long tasks_local = 0;   ///< computed by rank 0's own thread
  long tasks_remote = 0;  ///< computed by worker ranks and delivered
  long chunks = 0;        ///< task messages sent
  long largest_chunk = 0;
};

/// The rank-0 side. Call run() and broadcast() from the thread that created the
/// MpiSession (MPI_THREAD_FUNNELED). Its destructor releases the workers (they
/// return from serve()). A task that throws on a worker rank is rethrown by run()
/// (an io::InputError as such, anything else as std::runtime_error naming the
/// rank) after the other ranks dropped their chunks; so is one on rank 0.
class TaskFarm {
 public:
  explicit TaskFarm(const MpiSession& session);
  ~TaskFarm();
  TaskFarm(const TaskFarm&) = delete;
  TaskFarm& operator=(const TaskFarm&) = delete;

  /// Computes every task (here and on the workers); results reach on_result on
  /// this thread or rank 0's computing thread, one at a time. When *stop becomes
  /// true no new task starts.
  void run(const std::vector<std::vector<double>>& tasks, const ComputeFn& compute,
           const ResultFn& on_result, const std::atomic<bool>* stop = nullptr);
  /// Every worker receives `context` before any task sent after this call.
  void broadcast(const std::string& context);
  /// Tells every worker to return from serve(); called by the destructor.
  void release_workers();
  int ranks() const { return size_; }
  const FarmStats& stats() const { return stats_; }

 private:
  int size_;
  bool released_ = false;
  FarmStats stats_;
};

/// What a worker rank did until released.
struct WorkerStats {
  long tasks = 0, chunks = 0, contexts = 0;
  double compute_s = 0.0;  ///< computing tasks
  double idle_s = 0.0;     ///< holding no task (waiting for rank 0)
  double total_s = 0.0;    ///< the whole of serve()
};

/// The worker side (ranks > 0): computes the chunks rank 0 sends, and hands
/// contexts to on_context, until released.
WorkerStats serve(const ComputeFn& compute, const ContextFn& on_context = nullptr);

#endif

}  // namespace pronk::optimize::mpi
