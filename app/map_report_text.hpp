#pragma once
// The sentences `pronk map` prints about a finished map: where two models first disagree, and
// each row's boundary.
#include <string>

#include <nlohmann/json.hpp>

#include "optimize/map/map_engine.hpp"

namespace pronk::app {

/// Where along the first axis the two models first disagree, from summary.json's
/// "disagreement" (either value is null when there is none): "none anywhere on the grid ...",
/// "the first already at the grid's first ..." or "none up to ..., the first at ...".
std::string disagreement_sentence(const nlohmann::json& d, const std::string& axis);

/// One row's boundary: "boundary row 0: bisected duty_cycle = 0.3"; a "none_good" row names no
/// value (no cell of the row stabilized every trial).
std::string boundary_sentence(const optimize::map::BoundaryResult& b, const std::string& axis);

}  // namespace pronk::app
