// Where an evaluator's jobs (one evaluation's scenario runs and its stability
// analysis) run besides this process: the interface the evaluator sees, with
// MPI ranks behind it (optimize/mpi/evaluation_farm.hpp). Without a farm an
// evaluator runs its jobs on its own threads.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::optimize {

struct EvaluatorConfig;
class Evaluator;

class JobFarm {
 public:
  virtual ~JobFarm() = default;
  /// Makes an evaluator's configuration known wherever jobs run; its id.
  virtual long add_config(const EvaluatorConfig& config) = 0;
  /// Runs jobs {job, unit...} of evaluator `id` (`here` computes this process's
  /// share); results[i] is job i's Evaluator::compute_job answer, the same JSON
  /// wherever it ran.
  virtual std::vector<nlohmann::json> run(long id, const Evaluator& here,
                                          const std::vector<std::vector<double>>& jobs) = 0;
  /// "4 MPI ranks", for reports.
  virtual std::string describe() const = 0;
};

}  // namespace pronk::optimize
