// playback.json of a map: one trial per cell (trial 0 in the primary model) re-simulated
// with its trajectory sampled, so that report.html can play a cell's trial when it is
// clicked (a static page cannot simulate). The map's journal keeps only outcomes; these
// re-runs are deterministic, so they are the trials the map judged.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "optimize/map/map_study.hpp"

namespace pronk::optimize::map {

/// Numbers playback.json holds at most over all cells (about 2 MB).
inline constexpr long kPlaybackNumbers = 250000;

/// The playback document: {model, trial, columns, cells: [{cell, scene, touchdowns, data}]};
/// for a pseudo_rigid primary model {model, skipped: reason} (one full-model trial per cell
/// would cost 1/trials of the whole map again).
nlohmann::json map_playback_json(const MapStudy& st);

}  // namespace pronk::optimize::map
