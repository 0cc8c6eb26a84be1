// `pronk optimize` across MPI ranks: an evaluator's jobs (scenario runs and the
// stability analysis; every point of an Ipopt finite-difference batch at once)
// on the task farm. Rank 0 runs the optimizer and writes the journal; each
// evaluator configuration is broadcast once, and a job travels as
// {configuration id, job, unit point}. The numbers are those of a one-process run.
#pragma once

#include <string>
#include <vector>

#include "optimize/job_farm.hpp"
#include "optimize/mpi/task_farm.hpp"

namespace pronk::optimize::mpi {

#ifdef PRONK_WITH_MPI

/// The rank-0 side: a JobFarm over MPI ranks.
class MpiJobFarm final : public JobFarm {
 public:
  explicit MpiJobFarm(const MpiSession& session) : farm_(session) {}
  long add_config(const EvaluatorConfig& config) override;
  std::vector<nlohmann::json> run(long id, const Evaluator& here,
                                  const std::vector<std::vector<double>>& jobs) override;
  std::string describe() const override;
  /// Tells the workers to return from serve_evaluations().
  void release_workers() { farm_.release_workers(); }
  const FarmStats& stats() const { return farm_.stats(); }

 private:
  TaskFarm farm_;
  long configs_ = 0;
};

/// The worker side (ranks > 0): builds each configuration rank 0 broadcasts
/// and computes its jobs, until released.
WorkerStats serve_evaluations();

#endif

}  // namespace pronk::optimize::mpi
