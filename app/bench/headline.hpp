// The headline of `pronk bench`: the ratios of bench.json's "headline" against the
// targets of issues 3 (satellite), 4 (quad hopper vs MuJoCo) and 7 (stiffness growth).
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/suite.hpp"

namespace pronk::app {

/// The headline ratios against the targets of issues 3, 4 and 7.
nlohmann::json headline(const std::vector<bench::WorkPoint>& sat,
                        const std::vector<bench::WorkPoint>& sweep, const nlohmann::json& drop,
                        const nlohmann::json& cvode, const nlohmann::json& mujoco);

}  // namespace pronk::app
