#include "io/write/simulation_output.hpp"

#include "io/page/page_data.hpp"
#include "io/write/robot_output.hpp"
#include "sim/robot/fidelity.hpp"

namespace pronk::io {

namespace {
// The full-model run's strides against the pulse model of the same robot (milliseconds).
robot::FidelityDiscrepancy pulse_discrepancy(const scene::Scene& scene, const RunResult& r) {
  scene::Scene pulse = scene;
  pulse.model = scene::ModelKind::kPulse;
  RunOptions o;
  o.record_trajectory = false;
  return robot::compare_strides(simulate(pulse, o).run, r.run);
}
}  // namespace

nlohmann::json simulation_summary_json(const scene::Scene& scene, const RunResult& r,
                                       const reduced::RunMetrics& metrics) {
  if (!r.full_model()) return run_summary_json(scene, r.run, metrics);
  const robot::FidelityDiscrepancy fd = pulse_discrepancy(scene, r);
  return robot_summary_json(scene, r, metrics, &fd);
}

WrittenOutputs write_simulation_outputs(const std::string& dir, const scene::Scene& scene,
                                        const RunResult& r, const reduced::RunMetrics& metrics) {
  WrittenOutputs w;
  FigureBatch figures;
  if (!r.full_model()) {
    write_run_outputs(dir, scene, r.run, metrics, figures);
  } else {
    const robot::FidelityDiscrepancy fd = pulse_discrepancy(scene, r);
    write_robot_outputs(dir, scene, r, metrics, &fd, figures);
  }
  w.figures_rendered = figures.finish();  // every figure at once, at most one per core
  // view.html from the files just written: the page shows what is on disk.
  w.page = page::write_directory_page(dir);
  return w;
}

}  // namespace pronk::io
