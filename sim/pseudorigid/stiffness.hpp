// Automatic stiffness selection (docs/pseudorigid.md). Internal springs approximate
// rigidity and contact springs approximate hard ground: too soft and the body
// flexes (model error), too stiff and the ODE is stiffer than it needs to be.
// From a strain budget (allowed |l - l0| / l0 of internal springs) and a
// penetration budget [m], and an expected peak load, the stiffness is
//   internal: k = F_peak / (strain_budget * l_min), F_peak = M_body (n_g g + w0^2 r_max)
//             + the largest applied force on the body
//   contact:  k = n_g M_total g / penetration_budget
// where n_g (load_factor) is the expected peak load in body weights. The run
// reports the realised maximum strain and penetration, so the user sees
// whether the budget (and the pseudo-rigid approximation) held.
#pragma once

#include <string>

namespace pronk::pseudorigid {

struct Mechanism;

struct StiffnessSettings {
  bool internal_auto = false;
  bool contact_auto = false;
  double strain_budget = 1e-4;       ///< allowed internal strain (dimensionless)
  double penetration_budget = 1e-4;  ///< allowed contact penetration [m]
  double load_factor = 10.0;         ///< expected peak load in body weights
};

/// What choose_stiffness() did (for the summary).
struct StiffnessChoice {
  double internal_min = 0.0, internal_max = 0.0;  ///< chosen internal stiffness range [N/m]
  double contact = 0.0;                           ///< chosen contact stiffness [N/m]
  std::string note;
};

/// Applies the automatic choices to `m` (only where settings ask for "auto").
StiffnessChoice choose_stiffness(Mechanism& m, const StiffnessSettings& s);

}  // namespace pronk::pseudorigid
