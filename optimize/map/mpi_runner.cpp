#include "optimize/map/mpi_runner.hpp"

#ifdef PRONK_WITH_MPI

#include <stdexcept>

#include "sim/run/count_text.hpp"

namespace pronk::optimize::map {

namespace {

// A map task as the farm's payload: kind, index, good, bad.
std::vector<double> encode_map_task(const MapTask& t) {
  return {static_cast<double>(t.kind), static_cast<double>(t.index), t.good, t.bad};
}

MapTask decode_map_task(const std::vector<double>& d) {
  if (d.size() != 4) throw std::runtime_error("MPI: a malformed map task");
  MapTask t;
  t.kind = static_cast<int>(d[0]);
  t.index = static_cast<long>(d[1]);
  t.good = d[2];
  t.bad = d[3];
  return t;
}

}  // namespace

void MpiRunner::run(const MapStudy& st, const std::vector<MapTask>& tasks,
                    const std::function<void(const MapTask&, const nlohmann::json&)>& on_result,
                    const std::atomic<bool>* stop) {
  std::vector<std::vector<double>> payloads;
  payloads.reserve(tasks.size());
  for (const MapTask& t : tasks) payloads.push_back(encode_map_task(t));
  farm_.run(
      payloads, [&](const std::vector<double>& d) { return compute_task(st, decode_map_task(d)); },
      [&](long i, const nlohmann::json& r) { on_result(tasks[static_cast<size_t>(i)], r); }, stop);
}

std::string MpiRunner::describe() const {
  const int n = farm_.ranks();
  return run::count_text(n, "MPI rank");
}

MpiWorkerStats mpi_serve(const MapStudy& st) {
  return mpi::serve(
      [&](const std::vector<double>& d) { return compute_task(st, decode_map_task(d)); });
}

}  // namespace pronk::optimize::map

#endif
