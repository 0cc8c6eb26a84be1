#include "optimize/mpi/evaluation_farm.hpp"

#ifdef PRONK_WITH_MPI

#include <memory>
#include <stdexcept>

#include "optimize/evaluator.hpp"
#include "optimize/evaluator_wire.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::optimize::mpi {

long MpiJobFarm::add_config(const EvaluatorConfig& config) {
  farm_.broadcast(evaluator_config_to_wire(config).dump());
  return configs_++;
}

std::vector<nlohmann::json> MpiJobFarm::run(long id, const Evaluator& here,
                                            const std::vector<std::vector<double>>& jobs) {
  std::vector<std::vector<double>> tasks;
  tasks.reserve(jobs.size());
  for (const auto& j : jobs) {
    std::vector<double> t{static_cast<double>(id)};
    t.insert(t.end(), j.begin(), j.end());
    tasks.push_back(std::move(t));
  }
  std::vector<nlohmann::json> results(jobs.size());
  farm_.run(
      tasks,
      [&](const std::vector<double>& t) {
        return here.compute_job(std::vector<double>(t.begin() + 1, t.end()));
      },
      [&](long i, const nlohmann::json& r) { results[static_cast<size_t>(i)] = r; });
  return results;
}

std::string MpiJobFarm::describe() const {
  const int n = farm_.ranks();
  return run::count_text(n, "MPI rank");
}

WorkerStats serve_evaluations() {
  std::vector<std::unique_ptr<Evaluator>> evaluators;  // by configuration id
  return serve(
      [&](const std::vector<double>& t) {
        const long id = t.empty() ? -1 : static_cast<long>(t.front());
        if (id < 0 || id >= static_cast<long>(evaluators.size()))
          throw std::runtime_error("a job of an unknown evaluator configuration");
        return evaluators[static_cast<size_t>(id)]->compute_job(
            std::vector<double>(t.begin() + 1, t.end()));
      },
      [&](const std::string& context) {
        evaluators.push_back(std::make_unique<Evaluator>(
            evaluator_config_from_wire(nlohmann::json::parse(context))));
      });
}

}  // namespace pronk::optimize::mpi

#endif
