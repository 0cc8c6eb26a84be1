// Robustness-map studies (docs/maps.md): a scene, one or two axes, seeded disturbance
// trials per cell, one or two models to compare, the definition of
// "stabilized", and the boundary resolution. Loaded from `"kind": "map"` study
// files with the error discipline of docs/reliability.md (file, JSON Pointer, expected,
// found; unknown keys are errors).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "optimize/scenario.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize::map {

/// What an axis varies.
enum class AxisKind {
  kPointer,               ///< any number of the scene, by JSON Pointer (its own unit)
  kDutyCycle,             ///< pulse duration T = duty x nominal stride period [-]
  kTilt,                  ///< initial tilt about a body axis [deg]
  kLateralOffset,         ///< initial CoM offset along world y [m]
  kVelocityKick,          ///< initial horizontal velocity kick [m/s]
  kDisturbanceDirection,  ///< direction of the velocity kick in the horizontal plane [deg from +x]
};
std::string_view to_string(AxisKind k);

struct MapAxis {
  std::string name;  ///< column name in the CSV files (default: the kind, or the pointer)
  AxisKind kind = AxisKind::kDutyCycle;
  std::string pointer;                 ///< kPointer: JSON Pointer into the scene document
  std::vector<double> values;          ///< strictly increasing, in the axis unit
  bool log_scale = false;              ///< log spacing (range) and geometric bisection
  Eigen::Vector3d tilt_axis{1, 0, 0};  ///< kTilt: unit rotation axis in the body frame
  double direction_deg = 90.0;  ///< kVelocityKick: kick direction when no direction axis [deg]
  double magnitude = 0.0;       ///< kDisturbanceDirection: kick size when no kick axis [m/s]
  std::string unit() const;     ///< "-", "deg", "m", "m/s" or "" (pointer)
};

/// "Stabilized": the run neither fell nor diverged, and it settled — every
/// touchdown from stride k on has |x - x_d|, |y - y_d| < settle.position_error,
/// |roll|, |pitch| < settle.tilt and |apex - (l + h)| < settle.apex_error — with
/// k <= within_strides and at least hold_strides settled strides before the end.
struct StabilizedCriteria {
  reduced::SettleCriteria settle;
  long within_strides = 30;  ///< K: latest stride at which settling may start
  long hold_strides = 3;     ///< settled strides required at the end of the run
};

/// How a trial's random disturbance is seeded: mix(seed, key) and the trial
/// number, key = the row index (kRow: every cell of a row, and every bisection
/// probe of that row, sees the same N disturbances — common random numbers, so
/// the boundary along the row is a property of one trial set) or the cell index
/// (kCell: independent draws per cell; probes get keys past the last cell).
enum class Seeding { kRow, kCell };

struct MapStudy {
  std::string name;
  std::string file;           ///< where it was read from
  nlohmann::json document;    ///< the study as read (after overrides)
  std::string hash;           ///< FNV-1a 64 of the study and scene documents (hex)
  nlohmann::json scene_doc;   ///< resolved scene (every default explicit)
  std::string scene_file;     ///< names the scene in error messages
  scene::Scene base_scene;    ///< scene_doc parsed
  std::vector<MapAxis> axes;  ///< 1 or 2; axis 0 is the boundary axis (columns), axis 1 the rows
  /// Model A [, model B]: impulse, pulse or pseudo_rigid (the robot in the full model with the
  /// scene's "pseudo_rigid" settings: seconds per trial, not milliseconds); the last one is the
  /// primary model.
  std::vector<scene::ModelKind> models;
  RandomScenarios trials;  ///< count = trials per cell; seed = the study seed
  ScenarioSet trial_set;   ///< duration / stride limit of every trial (no scenarios)
  StabilizedCriteria stabilized;
  Seeding seeding = Seeding::kRow;
  /// Spectral radius of the primary model's stride map per distinct cell scene (pseudo_rigid:
  /// the estimate from reduced::estimate_stride_map, 4 runs of 6 s each).
  bool stability = true;
  double resolution = 0.0;  ///< boundary bisection stops when bad - good <= this (axis-0 unit)
  int max_bisection_steps = 40;
  std::string output_dir;  ///< default results/<name>

  long columns() const { return static_cast<long>(axes[0].values.size()); }
  long rows() const { return axes.size() > 1 ? static_cast<long>(axes[1].values.size()) : 1; }
  long cells() const { return columns() * rows(); }
  scene::ModelKind primary_model() const { return models.back(); }
};

/// Reads a map study; `overrides` ("/ptr=value") apply to the study document.
/// A scene given as a path is relative to the study file; it may also be a
/// design.json of `pronk optimize` (its resolved "scene" is used).
MapStudy load_map_study(const std::string& path, const std::vector<std::string>& overrides = {});

/// Parses a study document already read.
MapStudy parse_map_study(const nlohmann::json& doc, const std::string& file,
                         const std::string& base_dir);

/// Nominal stride period of a scene at pulse duration T [s]: T plus the
/// ballistic flight time 2 sqrt(2 h / g) of the hop-height law.
/// The duty axis solves duty = T / (T + 2 sqrt(2h/g)) for T.
double pulse_duration_for_duty(const scene::Scene& s, double duty);

/// What a duty axis sets in a scene's model: the pulse duration T, or, where the model times
/// the legs' thrust itself and lists /pulse/duration unused (the full model's spring legs on
/// the energy thrust), the leg spring stiffness whose stance half-period pi sqrt(m / (n k))
/// is that T. kNone: the model uses neither (a duty axis over it is refused).
enum class DutySetting { kPulseDuration, kLegStiffness, kNone };
DutySetting duty_setting(const scene::Scene& s);

/// Leg stiffness [N/m] of n spring legs carrying the body mass m whose stance half-period
/// pi sqrt(m / (n k)) is the pulse duration of `duty` (pulse_duration_for_duty).
double leg_stiffness_for_duty(const scene::Scene& s, double duty);

/// Sets what duty_setting(s) names for `duty`.
void apply_duty(scene::Scene& s, double duty);

}  // namespace pronk::optimize::map
