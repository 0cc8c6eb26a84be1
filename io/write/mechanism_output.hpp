// Writes one mechanism run into a directory (all files atomically):
//   nodes.csv     t [s], x/y/z [m] of every mass and ghost point
//   bodies.csv    t [s], per body: CoM [m], attitude as Euler angles of the chosen set
//                 (1-2-3 or 3-1-3) [rad], world angular velocity [rad/s]
//   energy.csv    t [s], kinetic, gravitational, applied, internal/leg/other/contact
//                 springs, dissipated, actuator work, total, balance [J]
//   summary.json  status, reason, cost counters, accuracy monitors, chosen stiffness
//   scene.resolved.json, energy.svg and motion.svg (gnuplot scripts beside them)
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "io/load/mechanism_loader.hpp"
#include "sim/pseudorigid/simulator.hpp"

namespace pronk::io {

nlohmann::json mechanism_summary_json(const LoadedMechanism& scene,
                                      const pseudorigid::RunSummary& run);
std::string mechanism_nodes_csv(const pseudorigid::Mechanism& m,
                                const pseudorigid::RunSummary& run);
std::string mechanism_bodies_csv(const pseudorigid::Mechanism& m,
                                 const pseudorigid::RunSummary& run);
std::string mechanism_energy_csv(const pseudorigid::RunSummary& run);

/// Writes every output file into `dir` (created if missing); returns true when
/// the figures were rendered (gnuplot available).
bool write_mechanism_outputs(const std::string& dir, const LoadedMechanism& scene,
                             const pseudorigid::RunSummary& run);

}  // namespace pronk::io
