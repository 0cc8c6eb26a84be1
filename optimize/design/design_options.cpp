#include "optimize/design/design_options.hpp"

#include <cmath>

namespace pronk::optimize {

namespace {

bool fail(std::string* err, const std::string& text) {
  *err = text;
  return false;
}

}  // namespace

bool DesignOptions::validate(std::string* err) const {
  if (final_model != "pulse" && final_model != "pseudo_rigid")
    return fail(err, "model: \"pulse\" or \"pseudo_rigid\", found \"" + final_model + "\"");
  if (full_optimizer != "cmaes" && full_optimizer != "bobyqa")
    return fail(err, "optimizer: \"cmaes\" or \"bobyqa\", found \"" + full_optimizer + "\"");
  if (pulse_evaluations < 1 || full_evaluations < 1) return fail(err, "budget: at least 1");
  if (full_optimizer == "cmaes" && population < 5) return fail(err, "population: at least 5");
  if (!(duty_lo > 0.0 && duty_hi > duty_lo && duty_hi < 0.9))
    return fail(err, "duty: 0 < low < high < 0.9");
  if (!(duty >= duty_lo && duty <= duty_hi)) return fail(err, "duty: the start within [low, high]");
  if (!(tilt_deg >= 0.0 && tilt_deg < 60.0)) return fail(err, "tilt: in [0, 60) degrees");
  if (!(lateral_offset >= 0.0 && std::isfinite(lateral_offset)))
    return fail(err, "offset: a finite number >= 0");
  if (!(velocity_kick >= 0.0 && std::isfinite(velocity_kick)))
    return fail(err, "kick: a finite number >= 0");
  if (!(mass >= 0.0 && mass < 1.0) || !(inertia >= 0.0 && inertia < 1.0) ||
      !(leg_stiffness >= 0.0 && leg_stiffness < 1.0))
    return fail(err, "perturb: relative half-widths in [0, 1)");
  if (!(friction_lo > 0.0 && friction_hi >= friction_lo && std::isfinite(friction_hi)))
    return fail(err, "friction: 0 < low <= high");
  if (scenarios < 1 || validation < 1) return fail(err, "trials: at least 1");
  if (!(duration > 0.0 && duration <= 600.0)) return fail(err, "duration: in (0, 600] s");
  if (seed < 0) return fail(err, "seed: >= 0");
  return true;
}

}  // namespace pronk::optimize
