#include "optimize/map/map_playback.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "io/load/scene_loader.hpp"
#include "optimize/map/map_engine.hpp"
#include "optimize/scenario.hpp"
#include "sim/simulate.hpp"

namespace pronk::optimize::map {

namespace {

double mapplay_round(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.5g", v);
  return std::strtod(buf, nullptr);
}

// One cell's trial 0: the scene, touchdown times and every `every`-th sample.
nlohmann::json mapplay_cell(const MapStudy& st, long cell, long max_rows) {
  const long row = cell_row(st, cell), col = cell_column(st, cell);
  const double v0 = st.axes[0].values[static_cast<size_t>(col)];
  const double v1 = st.axes.size() > 1 ? st.axes[1].values[static_cast<size_t>(row)] : 0.0;
  const scene::Scene base = scene_at(st, v0, v1, st.primary_model());
  const scene::Scene sc =
      apply_scenario(base, trial_scenario(st, cell_seed_key(st, cell), 0), st.trial_set);
  const reduced::RunResult run = simulate(sc).run;
  const auto& tr = run.trajectory;
  const long n = static_cast<long>(tr.size());
  const long every = std::max(1L, (n + max_rows - 1) / std::max(1L, max_rows));
  nlohmann::json data = nlohmann::json::array();
  for (int c = 0; c < 12; ++c) data.push_back(nlohmann::json::array());
  const double deg = 180.0 / M_PI;
  for (long i = 0; i < n; i = std::min(i + every, n - 1)) {
    const auto& s = tr[static_cast<size_t>(i)];
    const double v[12] = {s.t,
                          s.position[0],
                          s.position[1],
                          s.position[2],
                          s.euler123[0] * deg,
                          s.euler123[1] * deg,
                          s.euler123[2] * deg,
                          s.setpoint[0],
                          s.setpoint[1],
                          s.leg_force_world[0],
                          s.leg_force_world[1],
                          s.leg_force_world[2]};
    for (int c = 0; c < 12; ++c) data[static_cast<size_t>(c)].push_back(mapplay_round(v[c]));
    if (i == n - 1) break;
  }
  nlohmann::json td = nlohmann::json::array();
  for (const auto& s : run.strides) td.push_back(mapplay_round(s.t_touchdown));
  return {{"cell", cell},
          {"status", std::string(reduced::to_string(run.status))},
          {"scene", io::scene_to_json(sc)},
          {"touchdowns", td},
          {"data", data}};
}

}  // namespace

nlohmann::json map_playback_json(const MapStudy& st) {
  const std::string model(scene::to_string(st.primary_model()));
  if (scene::is_full_model(st.primary_model())) {
    return {{"model", model},
            {"skipped", "no playback for a " + model +
                            " map: re-simulating one full-model trial per cell "
                            "would cost a fraction 1/trials of the whole map again"}};
  }
  const long cells = st.cells();
  const long max_rows = std::max(20L, kPlaybackNumbers / (12 * std::max(1L, cells)));
  nlohmann::json out = {
      {"model", model},
      {"trial", 0},
      {"columns",
       {"t", "x", "y", "z", "roll_deg", "pitch_deg", "yaw_deg", "x_d", "y_d", "Fx", "Fy", "Fz"}},
      {"cells", nlohmann::json::array()}};
  for (long c = 0; c < cells; ++c) out["cells"].push_back(mapplay_cell(st, c, max_rows));
  return out;
}

}  // namespace pronk::optimize::map
