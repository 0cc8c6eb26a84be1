// An upper bound on a mechanism's highest natural frequency: the stability limit of the
// explicit and symplectic fixed-step methods (velocity Verlet is stable for h < 2 / omega_max).
#pragma once

#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

/// An upper bound on the highest angular frequency [rad/s] of the mechanism's springs
/// (connections and surfaces, at their stiffness), from Gershgorin's theorem on M^-1 K:
/// omega_max^2 <= max_i (1 / m_i) sum_e k_e |c_ei| sum_j |c_ej| over the elements e
/// acting on mass i, c_e the element's weights on the masses (1 for a mass node, the
/// barycentric weights for a ghost point, opposite signs at the two ends). Projections
/// (a plane's normal, a line's cross directions) only lower the true value. 0 without
/// springs.
double max_frequency_bound(const Mechanism& m);

}  // namespace pronk::pseudorigid
