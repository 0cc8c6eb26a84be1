// What a run may change of a Mechanism as it goes, beside the const Mechanism (MuJoCo's mjData
// beside its mjModel): the connections' rest lengths and the surfaces' kind, sidedness and
// direction, and whether a surface holds its nodes. A run owns one, initialised from the
// Mechanism; a MechanismSystem reads these instead of the Mechanism's fields, and the run's
// controller (the robot's hip placement and foot switches) writes them between integration
// segments. Every other field of the Mechanism is fixed for the run.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

/// The run-time part of one Surface (its other fields are the Mechanism's).
struct SurfaceInputs {
  SurfaceType type = SurfaceType::kPlane;
  bool bilateral = false;  ///< plane: holds on both sides
  /// Unit normal (plane) or direction (line); body frame when attached (Surface::direction).
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  bool holds = true;  ///< false: the surface constrains none of its nodes
  bool operator==(const SurfaceInputs&) const = default;
};

struct MechanismInputs {
  MechanismInputs() = default;
  /// The inputs as the Mechanism has them.
  explicit MechanismInputs(const Mechanism& m) {
    for (const Connection& c : m.connections) rest_length.push_back(c.rest_length);
    for (const Surface& s : m.surfaces) surfaces.push_back({s.type, s.bilateral, s.direction});
  }
  std::vector<double> rest_length;      ///< per connection: its rest length l0 [m]
  std::vector<SurfaceInputs> surfaces;  ///< per surface
};

}  // namespace pronk::pseudorigid
