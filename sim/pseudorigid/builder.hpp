// Helpers that add components to a Mechanism under construction (used by the
// JSON loader, the tests and the benchmarks alike).
#pragma once

#include <string>

#include "sim/pseudorigid/model.hpp"

namespace pronk::pseudorigid {

/// Adds a free point mass; returns its node.
NodeRef add_mass(Mechanism& m, const std::string& name, double mass,
                 const Eigen::Vector3d& position,
                 const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero());

/// Builds a body (four masses, six internal springs with optional dampers).
/// Returns the body index, or -1 with *error set for an invalid tensor.
int add_body(Mechanism& m, const BodySpec& spec, std::string* error);

/// Adds a ghost point at body-frame location `local` (relative to the CoM) [m].
NodeRef add_ghost_point(Mechanism& m, int body, const std::string& name,
                        const Eigen::Vector3d& local);

/// Adds a reference point; returns its index.
int add_reference_point(Mechanism& m, int body, const std::string& name,
                        const Eigen::Vector3d& local);

/// Adds a dummy mass of dummy_ratio * body mass at body-frame `local`, tied to
/// the four body masses by connections of the body's internal stiffness.
NodeRef add_dummy_mass(Mechanism& m, int body, const std::string& name,
                       const Eigen::Vector3d& local, double dummy_ratio, double stiffness,
                       double damping);

/// Adds a grounded anchor; returns its node.
NodeRef add_anchor(Mechanism& m, const std::string& name, const Eigen::Vector3d& position);

/// Sets the stiffness of every internal connection (and dummy-mass tie) of all bodies [N/m].
void set_internal_stiffness(Mechanism& m, double k);

}  // namespace pronk::pseudorigid
