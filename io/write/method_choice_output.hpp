// What "method": "auto" chose, for summary.json (mechanism and robot runs alike):
//   "method_choice": the one-line reason (pseudorigid::MethodChoice::reason)
//   "auto": {"method", "rule", "h_fixed_s" | "rtol"/"atol", "energy_tol", "accuracy",
//            "omega_max_rad_s", "omega_bound_rad_s", "min_mass_kg", "contact", "dissipation",
//            "energy_balance_drift_relative" (the run's), "accuracy_met",
//            "reruns" (1: the first run missed the accuracy and was rerun tighter),
//            "first_run_drift_relative" (when rerun)}
#pragma once

#include <nlohmann/json.hpp>

#include "sim/pseudorigid/method_choice.hpp"

namespace pronk::io {

/// Adds "method_choice" and "auto" to a summary; `drift_relative`: the run's largest sampled
/// energy-balance drift over its energy scale.
void add_method_choice(const pseudorigid::MethodChoice& c, double drift_relative,
                       nlohmann::json* summary);

}  // namespace pronk::io
