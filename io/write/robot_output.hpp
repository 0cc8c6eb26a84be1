// Outputs of a robot run in the full (pseudo-rigid) model: everything the
// reduced models write (trajectory.csv, strides.csv with the same columns,
// summary.json, scene.resolved.json, motion/strides figures) plus energy.csv
// (energy by class), feet.csv (actuator and ground forces, foot heights),
// a pseudo_rigid section in summary.json (accuracy monitors: energy balance,
// max strain, max penetration, slip; stiffness used) and the seed's figures:
// hop height and foot forces vs time, energy by class, 3-D path.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "io/write/run_output.hpp"
#include "sim/robot/fidelity.hpp"
#include "sim/robot/robot_simulator.hpp"

namespace pronk::io {

/// The summary document of a full-model run.
/// `pulse` (optional): discrepancy against the pulse model of the same robot.
nlohmann::json robot_summary_json(const scene::Scene& scene, const robot::RobotRunResult& r,
                                  const reduced::RunMetrics& metrics,
                                  const robot::FidelityDiscrepancy* pulse = nullptr);

/// energy.csv and feet.csv as tables and as text.
Table robot_energy_table(const robot::RobotRunResult& r);
Table robot_feet_table(const robot::RobotRunResult& r);
std::string robot_energy_csv(const robot::RobotRunResult& r);
std::string robot_feet_csv(const robot::RobotRunResult& r);

/// The reduced run's files (write_run_files) with the full model's summary.json, and
/// energy.csv, feet.csv, a MuJoCo run's robot.xml; the figures added to `figures`.
void write_robot_outputs(const std::string& dir, const scene::Scene& scene,
                         const robot::RobotRunResult& r, const reduced::RunMetrics& metrics,
                         const robot::FidelityDiscrepancy* pulse, FigureBatch& figures);

}  // namespace pronk::io
