// pronk map across MPI ranks (optional: built when CMake finds MPI, which
// defines PRONK_WITH_MPI). Rank 0 owns the study outputs and the journal; it
// computes tasks itself on a second thread and hands the others out to ranks
// 1..N-1 in guided chunks (several tasks per message, the chunk shrinking with
// the work left: max(1, left / (4 N)); dynamic load balancing, since cells
// differ in cost). Every worker rank holds two chunks (it computes one while
// the next waits), so it never idles for a round trip, and answers each chunk
// with one message of its results. Results travel as the journal's JSON text
// (doubles exact), so the outputs are bit-identical to a one-process run.
// Nobody busy-waits: idle ranks poll with sleeps of 50 us growing to 1 ms (a
// blocking MPI receive spins a core that a computing rank needs).
#pragma once

#include <string>
#include <vector>

#include "optimize/map/map_runner.hpp"

namespace pronk::optimize::map {

/// True when this build has MPI.
bool mpi_built();

/// True when the process was started by mpirun/mpiexec with more than one rank
/// (OpenMPI, MPICH/Hydra or PMIx environment variables).
bool mpi_launched();

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

/// What rank 0 did (summed over the runs of one MpiRunner).
struct MpiRunStats {
  long tasks_local = 0;   ///< computed by rank 0's own thread
  long tasks_remote = 0;  ///< computed by worker ranks and delivered
  long chunks = 0;        ///< task messages sent
  long largest_chunk = 0;
};

/// The rank-0 side: distributes tasks to ranks 1..size-1 and computes on a
/// local thread. Its destructor releases the workers (they return from mpi_serve()).
/// A task that throws on a worker rank is rethrown here (an io::InputError as
/// such, anything else as std::runtime_error naming the rank) after the other
/// ranks dropped their chunks; so is one on rank 0.
class MpiRunner final : public TaskRunner {
 public:
  explicit MpiRunner(const MpiSession& session);
  ~MpiRunner() override;
  void run(const MapStudy& st, const std::vector<MapTask>& tasks,
           const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
           const std::atomic<bool>* stop) override;
  std::string describe() const override;
  /// Tells every worker to return from mpi_serve(); called by the destructor.
  void release_workers();
  const MpiRunStats& stats() const { return stats_; }

 private:
  int size_;
  bool released_ = false;
  MpiRunStats stats_;
};

/// What a worker rank did until released.
struct MpiWorkerStats {
  long tasks = 0, chunks = 0;
  double compute_s = 0.0;  ///< computing tasks
  double idle_s = 0.0;     ///< holding no task (waiting for rank 0)
  double total_s = 0.0;    ///< the whole of mpi_serve()
};

/// The worker side (ranks > 0): computes the chunks rank 0 sends until released.
MpiWorkerStats mpi_serve(const MapStudy& st);

#endif

}  // namespace pronk::optimize::map
