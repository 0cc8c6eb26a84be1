// The scene readers' side of "method": "auto" (mechanisms and full-model robots alike): auto
// chooses the step and the tolerances, so the input must not set them.
#pragma once

#include <nlohmann/json.hpp>

#include "io/load/json_reader.hpp"

namespace pronk::io {

/// Under "method": "auto" (named, or the default when `solver` has no "method"), a value for a
/// setting auto chooses (pseudorigid::kAutoChosenSettings: rtol, atol, h_fixed, energy_tol) is
/// an input error at its pointer, not a setting silently replaced. `node` is the object `solver`
/// reads.
void refuse_auto_chosen_settings(JsonReader& solver, const nlohmann::json& node);

}  // namespace pronk::io
