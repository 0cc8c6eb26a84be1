// Metrics of a scenario run, their aggregation over the scenario set, and the
// objective (weighted terms) and constraints (metric bounds) built from them.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "sim/reduced/metrics.hpp"
#include "sim/reduced/run_result.hpp"
#include "sim/scene/scene.hpp"
#include "sim/simulate.hpp"

namespace pronk::optimize {

/// Names of the per-scenario metrics (all finite):
///   hop_height_error   RMS of apex - (l + h) over strides after the first [m]
///   x_error, y_error   RMS of x - x_d, y - y_d at touchdowns [m]
///   attitude_error     RMS attitude error (roll, pitch, yaw - yaw_d) at touchdowns [rad]
///   final_error        horizontal distance to the setpoint at the end [m]
///   settle_strides     strides until settled (SettleCriteria); runs that never settle: strides + 1
///   stabilized         1 if the run settled and did not fall, else 0
///   duty_max, duty_mean  stance / stride time [-]
///   peak_leg_force     [N]
///   effort_per_stride  mean delivered |P| per stride [N s]
///   fell               1 if the run fell or diverged, else 0
///   spectral_radius    of the stride map at the periodic orbit (a property of the design)
///   apex_held          1 if the run did not fall and every apex after the fifth stride is
///                      within 3 % of the target hop height h of l + h, else 0
/// The full (pseudo-rigid) model adds its accuracy monitors and actuator costs:
///   energy_drift       max |energy balance(t) - balance(0)| / energy scale [-]
///   max_strain         largest internal spring strain [-]
///   max_penetration    deepest ground penetration or slide violation [m]
///   max_slip           largest horizontal foot travel within one stance [m]
///   peak_actuator_force  largest |leg actuator force| over the strides [N]
///   actuator_work_per_m  positive actuator work (legs and hip placement) per metre of
///                      horizontal CoM travel (at least 1 cm) [J/m]
///   cost_of_transport  actuator_work_per_m / (M g) [-]
/// A run that fell gets its error metrics raised to at least
/// fall_penalty * (2 - t_fall / duration): between 1x and 2x the penalty, more
/// for an earlier fall.
/// The metrics a model reports (the reduced models' list, plus the full model's own).
const std::vector<std::string>& metric_names(scene::ModelKind model);
/// A metric of some model.
bool is_metric(const std::string& name);
/// A metric `model` reports.
bool is_metric(const std::string& name, scene::ModelKind model);

using MetricMap = std::map<std::string, double>;

MetricMap scenario_metrics(const scene::Scene& scene, const RunResult& result,
                           double fall_penalty = 1.0, const reduced::SettleCriteria& criteria = {});

enum class Aggregate { kMean, kWorst, kCvar };
std::string_view to_string(Aggregate a);

/// Mean, worst (max), or CVaR_alpha: the mean of the worst ceil(alpha n) values.
double aggregate(const std::vector<double>& values, Aggregate how, double alpha);

struct ObjectiveTerm {
  std::string metric;
  double weight = 1.0;
  Aggregate how = Aggregate::kMean;
  double alpha = 0.2;
};

struct ConstraintSpec {
  std::string metric;
  Aggregate how = Aggregate::kWorst;
  double alpha = 0.2;
  bool has_max = false, has_min = false;
  double max = 0.0, min = 0.0;
  /// Constraint values g <= 0: (agg - max) and/or (min - agg).
  std::string label() const;
};

}  // namespace pronk::optimize
