#include "sim/io/simulation_output.hpp"

#include "sim/io/robot_output.hpp"
#include "sim/robot/fidelity.hpp"

namespace pronk::io {

WrittenOutputs write_simulation_outputs(const std::string& dir, const scene::Scene& scene,
                                        const RunResult& r, const reduced::RunMetrics& metrics) {
  if (!r.full_model()) return write_run_outputs(dir, scene, r.run, metrics);
  scene::Scene pulse = scene;
  pulse.model = scene::ModelKind::kPulse;
  RunOptions o;
  o.record_trajectory = false;
  const robot::FidelityDiscrepancy fd = robot::compare_strides(simulate(pulse, o).run, r.run);
  return write_robot_outputs(dir, scene, r, metrics, &fd);
}

}  // namespace pronk::io
