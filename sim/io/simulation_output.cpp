#include "sim/io/simulation_output.hpp"

#include "sim/io/page/page_data.hpp"
#include "sim/io/robot_output.hpp"
#include "sim/robot/fidelity.hpp"

namespace pronk::io {

WrittenOutputs write_simulation_outputs(const std::string& dir, const scene::Scene& scene,
                                        const RunResult& r, const reduced::RunMetrics& metrics) {
  WrittenOutputs w;
  if (!r.full_model()) {
    w = write_run_outputs(dir, scene, r.run, metrics);
  } else {
    scene::Scene pulse = scene;
    pulse.model = scene::ModelKind::kPulse;
    RunOptions o;
    o.record_trajectory = false;
    const robot::FidelityDiscrepancy fd = robot::compare_strides(simulate(pulse, o).run, r.run);
    w = write_robot_outputs(dir, scene, r, metrics, &fd);
  }
  // view.html from the files just written: the page shows what is on disk.
  w.page = page::write_directory_page(dir);
  return w;
}

}  // namespace pronk::io
