// The probe of a mechanism that "method": "auto" chooses from (method_choice.hpp): its
// highest natural frequency, smallest mass, contact and dissipation, read from the built
// mechanism at its initial configuration without integrating it.
#pragma once

#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

/// What the probe found. Frequencies are angular [rad/s].
struct SceneProbe {
  /// Highest natural frequency of the undamped springs with every surface engaged (feet
  /// pressed on the ground, slides holding), at the initial configuration: the square root
  /// of the largest eigenvalue of M^-1/2 K M^-1/2 by power iteration, K assembled from each
  /// element's 3x3 stiffness along its directions (a spring k d d^T plus its tension's
  /// k (1 - l0/l) across, a plane k n n^T, a line k (1 - d d^T), a point k 1). Verlet is
  /// stable for h < 2 / omega_max. 0 without springs.
  double omega_max = 0.0;
  /// Gershgorin's upper bound on the same frequency (max_frequency_bound, stability.hpp),
  /// which ignores directions: omega_max <= omega_bound.
  double omega_bound = 0.0;
  /// Highest frequency sqrt(k / m) of a node on an elastic one-sided plane (damping ratio
  /// c / 2 sqrt(k m) below 0.1): a contact that rings, so each impact is a few periods of
  /// it. 0 without one [rad/s].
  double omega_elastic_contact = 0.0;
  double min_mass = 0.0;     ///< smallest point mass [kg]
  bool contact = false;      ///< a one-sided plane (ground or body-attached): non-smooth
  bool dissipation = false;  ///< dampers, friction or drag on a connection or surface
  /// Verlet can take the dissipation implicitly (its dissipation split); false when a
  /// dissipative element acts on a ghost point under the min_norm transfer (then the
  /// dampers sit in Verlet's explicit kicks and bound its step too).
  bool dissipation_split = true;
  int springs = 0;  ///< connections and surfaces with stiffness > 0
};

/// Probes m (deterministic: a fixed start vector and iteration count).
SceneProbe probe_scene(const Mechanism& m);

}  // namespace pronk::pseudorigid
