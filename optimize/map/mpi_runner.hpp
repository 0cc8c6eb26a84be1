// pronk map across MPI ranks: the map's tasks (cells, row bisections) on the
// task farm of optimize/mpi/task_farm.hpp. Rank 0 owns the study outputs and the
// journal; results travel as the journal's JSON text, so the outputs are
// bit-identical to a one-process run.
#pragma once

#include <string>
#include <vector>

#include "optimize/map/map_runner.hpp"
#include "optimize/mpi/task_farm.hpp"

namespace pronk::optimize::map {

using mpi::mpi_built;
using mpi::mpi_launched;

#ifdef PRONK_WITH_MPI

using mpi::MpiSession;
using MpiRunStats = mpi::FarmStats;
using MpiWorkerStats = mpi::WorkerStats;

/// The rank-0 side: the map's tasks on the farm. Its destructor releases the
/// workers (they return from mpi_serve()).
class MpiRunner final : public TaskRunner {
 public:
  explicit MpiRunner(const MpiSession& session) : farm_(session) {}
  void run(const MapStudy& st, const std::vector<MapTask>& tasks,
           const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
           const std::atomic<bool>* stop) override;
  std::string describe() const override;
  /// Tells every worker to return from mpi_serve(); called by the destructor.
  void release_workers() { farm_.release_workers(); }
  const MpiRunStats& stats() const { return farm_.stats(); }

 private:
  mpi::TaskFarm farm_;
};

/// The worker side (ranks > 0): computes the map's tasks until released.
MpiWorkerStats mpi_serve(const MapStudy& st);

#endif

}  // namespace pronk::optimize::map
