// pronk map across MPI ranks (optional: built when CMake finds MPI, which
// defines PRONK_WITH_MPI). Rank 0 owns the study outputs and the journal and
// hands out tasks one at a time as ranks ask for them (dynamic load
// balancing: cells differ in cost); it computes tasks itself on a second
// thread meanwhile, so N ranks are N workers. Results travel as the journal's
// JSON (doubles exact), so the outputs are bit-identical to a one-process run.
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

/// MPI_Init_thread (funneled) / MPI_Finalize around a scope.
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

/// The rank-0 side: distributes tasks to ranks 1..size-1 and computes on a
/// local thread. Its destructor releases the workers (they return from serve()).
class MpiRunner final : public TaskRunner {
 public:
  explicit MpiRunner(const MpiSession& session);
  ~MpiRunner() override;
  void run(const MapStudy& st, const std::vector<MapTask>& tasks,
           const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
           const std::atomic<bool>* stop) override;
  std::string describe() const override;
  /// Tells every worker to return from serve(); called by the destructor.
  void release_workers();

 private:
  int size_;
  std::vector<int> idle_;      ///< workers waiting for a task
  std::vector<bool> greeted_;  ///< worker's first "ready" received
  bool released_ = false;
};

/// The worker side (ranks > 0): computes the tasks rank 0 sends until released.
void mpi_serve(const MapStudy& st);

#endif

}  // namespace pronk::optimize::map
