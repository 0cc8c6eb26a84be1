// Tiny robustness-map studies shared by the map tests (seconds, not minutes).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "optimize/map/map_study.hpp"

namespace pronk::test {

/// The seed's legged pulse scene (case 3) started level at the nominal height,
/// a duty-cycle axis across the seed's limit, `trials` trials of `duration` s.
inline nlohmann::json tiny_map_document(long columns = 4, long trials = 3, double duration = 6.0) {
  using nlohmann::json;
  return json{
      {"name", "tiny_map"},
      {"kind", "map"},
      {"scene", std::string(PRONK_SOURCE_DIR) + "/studies/scenes/case3_legged_pulse.json"},
      {"scene_overrides", {"/initial/position=[0, 0, 0.45]", "/initial/attitude_deg=[0, 0, 0]"}},
      {"axes",
       {{{"kind", "duty_cycle"}, {"range", {0.2, 0.4}}, {"count", columns}},
        {{"kind", "tilt_deg"}, {"values", {0, 8}}}}},
      {"trials",
       {{"count", trials},
        {"seed", 7},
        {"duration", duration},
        {"tilt_deg", {0, 10}},
        {"lateral_offset", {0, 0.4}}}},
      {"boundary", {{"resolution", 0.01}}}};
}

inline optimize::map::MapStudy tiny_map(long columns = 4, long trials = 3, double duration = 6.0) {
  return optimize::map::parse_map_study(tiny_map_document(columns, trials, duration), "tiny.json",
                                        ".");
}

}  // namespace pronk::test
