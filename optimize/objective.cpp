#include "optimize/objective.hpp"

#include <algorithm>
#include <cmath>

#include "sim/math/rotation.hpp"

namespace pronk::optimize {

namespace {

const std::vector<std::string>& reduced_metric_names() {
  static const std::vector<std::string> names = {
      "hop_height_error",  "x_error",    "y_error",         "attitude_error", "final_error",
      "settle_strides",    "stabilized", "duty_max",        "duty_mean",      "peak_leg_force",
      "effort_per_stride", "fell",       "spectral_radius", "apex_held"};
  return names;
}

// The metrics only the full model reports.
const std::vector<std::string>& full_only_metric_names() {
  static const std::vector<std::string> names = {
      "energy_drift",        "max_strain",          "max_penetration",  "max_slip",
      "peak_actuator_force", "actuator_work_per_m", "cost_of_transport"};
  return names;
}

const std::vector<std::string>& full_metric_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = reduced_metric_names();
    n.insert(n.end(), full_only_metric_names().begin(), full_only_metric_names().end());
    return n;
  }();
  return names;
}

// The full model's own metrics: its accuracy monitors and actuator costs.
void add_full_metrics(const scene::Scene& scene, const RunResult& r, MetricMap& out) {
  const auto& m = r.monitors;
  out["energy_drift"] = m.energy_scale > 0 ? m.energy_drift / m.energy_scale : 0.0;
  out["max_strain"] = m.max_strain;
  out["max_penetration"] = m.max_penetration;
  out["max_slip"] = m.max_slip;
  double peak = 0.0;
  for (const auto& stride : r.stride_actuator_force)
    for (double f : stride) peak = std::max(peak, std::abs(f));
  out["peak_actuator_force"] = peak;
  const Eigen::Vector2d travel = (r.run.final_position - scene.initial.position).head<2>();
  const double per_m = m.positive_actuator_work / std::max(travel.norm(), 0.01);
  out["actuator_work_per_m"] = per_m;
  double mass = scene.body.mass;
  if (scene.pseudo_rigid.legs == scene::PseudoRigid::Legs::kSpring)
    mass += scene.pseudo_rigid.foot_mass * static_cast<double>(scene.legs.hips.size());
  out["cost_of_transport"] = per_m / (mass * scene.gravity);
  for (const std::string& k : full_only_metric_names()) {
    out[k] = std::min(out[k], 1e9);  // a diverged run's monitors are huge, not infinite
  }
}

}  // namespace

const std::vector<std::string>& metric_names(scene::ModelKind model) {
  return scene::is_full_model(model) ? full_metric_names() : reduced_metric_names();
}

bool is_metric(const std::string& name) {
  const auto& n = full_metric_names();
  return std::find(n.begin(), n.end(), name) != n.end();
}

bool is_metric(const std::string& name, scene::ModelKind model) {
  const auto& n = metric_names(model);
  return std::find(n.begin(), n.end(), name) != n.end();
}

std::string_view to_string(Aggregate a) {
  switch (a) {
    case Aggregate::kMean:
      return "mean";
    case Aggregate::kWorst:
      return "worst";
    case Aggregate::kCvar:
      return "cvar";
  }
  return "?";
}

namespace {
constexpr long kApexHeldAfter = 5;          // strides 0-4 (the first five) are the transient
constexpr double kApexHeldFraction = 0.03;  // of the target hop height h
}  // namespace

MetricMap scenario_metrics(const scene::Scene& scene, const RunResult& result, double fall_penalty,
                           const reduced::SettleCriteria& criteria) {
  const reduced::RunResult& run = result.run;
  const reduced::RunMetrics m = reduced::compute_metrics(scene, run, criteria);
  const double target_apex = scene.legs.length + scene.controller.hop_height;
  double apex2 = 0, x2 = 0, y2 = 0, att2 = 0, late_apex = 0;
  long n_apex = 0, n = 0;
  for (const auto& s : run.strides) {
    if (s.has_apex && s.index > 0) {
      apex2 += std::pow(s.apex_height - target_apex, 2);
      ++n_apex;
    }
    if (s.has_apex && s.index >= kApexHeldAfter) {
      late_apex = std::max(late_apex, std::abs(s.apex_height - target_apex));
    }
    x2 += std::pow(s.position.x() - s.setpoint.x(), 2);
    y2 += std::pow(s.position.y() - s.setpoint.y(), 2);
    const math::Quat q = math::euler_to_quat(s.euler123, math::EulerSet::k123);
    const math::Quat qd(Eigen::AngleAxisd(scene.controller.setpoint_yaw, Eigen::Vector3d::UnitZ()));
    att2 += math::quat_to_rotation_vector(qd.conjugate() * q).squaredNorm();
    ++n;
  }
  auto rms = [](double sum, long count) { return count > 0 ? std::sqrt(sum / count) : 0.0; };
  const bool fell = run.status != reduced::RunStatus::kCompleted;
  MetricMap out;
  out["hop_height_error"] = rms(apex2, n_apex);
  out["x_error"] = rms(x2, n);
  out["y_error"] = rms(y2, n);
  out["attitude_error"] = rms(att2, n);
  out["final_error"] = std::hypot(m.final_x_error, m.final_y_error);
  out["settle_strides"] = m.settle_strides >= 0 ? static_cast<double>(m.settle_strides)
                                                : static_cast<double>(m.strides + 1);
  out["stabilized"] = (!fell && m.settle_strides >= 0) ? 1.0 : 0.0;
  out["duty_max"] = m.max_duty;
  out["duty_mean"] = m.mean_duty;
  out["peak_leg_force"] = m.peak_leg_force;
  out["effort_per_stride"] = m.mean_impulse_per_stride;
  out["fell"] = fell ? 1.0 : 0.0;
  out["apex_held"] =
      (!fell && late_apex <= kApexHeldFraction * scene.controller.hop_height) ? 1.0 : 0.0;
  out["spectral_radius"] = 0.0;  // filled per design by the evaluator
  if (result.full_model()) add_full_metrics(scene, result, out);
  if (fell) {
    // At least the penalty, more the earlier it fell: a fallen design still
    // tells an optimizer which way is better.
    const double lived = std::clamp(run.t_end / scene.simulation.duration, 0.0, 1.0);
    const double penalty = fall_penalty * (2.0 - lived);
    for (const char* k :
         {"hop_height_error", "x_error", "y_error", "attitude_error", "final_error"}) {
      out[k] = std::max(out[k], penalty);
    }
  }
  for (auto& [k, v] : out) {
    if (!std::isfinite(v)) v = fall_penalty * 1e3;  // defensive: never hand on NaN
  }
  return out;
}

double aggregate(const std::vector<double>& values, Aggregate how, double alpha) {
  if (values.empty()) return 0.0;
  switch (how) {
    case Aggregate::kMean: {
      double s = 0;
      for (double v : values) s += v;
      return s / static_cast<double>(values.size());
    }
    case Aggregate::kWorst:
      return *std::max_element(values.begin(), values.end());
    case Aggregate::kCvar: {
      std::vector<double> v = values;
      std::sort(v.begin(), v.end(), std::greater<>());
      const size_t k =
          std::max<size_t>(1, static_cast<size_t>(std::ceil(alpha * v.size() - 1e-12)));
      double s = 0;
      for (size_t i = 0; i < k && i < v.size(); ++i) s += v[i];
      return s / static_cast<double>(std::min(k, v.size()));
    }
  }
  return 0.0;
}

std::string ConstraintSpec::label() const {
  std::string s = std::string(to_string(how)) + "(" + metric + ")";
  if (has_max) s += " <= " + std::to_string(max);
  if (has_min) s += " >= " + std::to_string(min);
  return s;
}

}  // namespace pronk::optimize
