#include "sim/reduced/run_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace pronk::reduced {

namespace {
/// x with 6 significant digits, as the run reasons print numbers (run::fmt; this file
/// stays free of the run loop so the scene loader's fuzz target can link it alone).
std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

/// The lowest hop height the controller is asked for over the run [m].
double lowest_hop_height(const scene::Scene& s) {
  double lowest = s.controller.hop_height;
  for (const auto& change : s.controller.hop_height_changes) {
    lowest = std::min(lowest, change.second);
  }
  return lowest;
}
}  // namespace

double trajectory_samples(const scene::Simulation& sim) {
  return sim.duration / sim.sample_interval;
}

std::optional<LimitBreach> memory_limit_breach(const scene::Simulation& sim, bool trajectory,
                                               bool strides) {
  const double samples = trajectory_samples(sim);
  if (trajectory && !(samples <= kMaxSamples)) {
    return LimitBreach{"sample_interval",
                       "at most " + fmt(kMaxSamples) +
                           " trajectory samples held in memory (duration / sample_interval)",
                       fmt(samples) + " samples (duration " + fmt(sim.duration) +
                           " s / sample_interval " + fmt(sim.sample_interval) + " s)"};
  }
  if (strides && sim.max_strides > kMaxStrides) {
    return LimitBreach{
        "max_strides",
        "at most " + fmt(static_cast<double>(kMaxStrides)) + " stride records held in memory",
        "max_strides " + fmt(static_cast<double>(sim.max_strides))};
  }
  return std::nullopt;
}

void require_memory_limits(const scene::Simulation& sim, bool trajectory, bool strides) {
  if (const auto b = memory_limit_breach(sim, trajectory, strides)) {
    throw std::invalid_argument("simulation." + b->field + ": " + b->reason());
  }
}

double max_fixed_step(const scene::Scene& s) {
  if (!(s.gravity > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(2.0 * lowest_hop_height(s) / s.gravity);
}

std::optional<LimitBreach> fixed_step_breach(const scene::Scene& s,
                                             const ode::SolverOptions& solver) {
  const double limit = max_fixed_step(s);
  if (ode::is_adaptive(solver.method) || solver.h_fixed <= limit) return std::nullopt;
  return LimitBreach{
      "h_fixed",
      "a fixed step of at most " + fmt(limit) + " s, half the " + fmt(2.0 * limit) +
          " s flight of the lowest hop height " + fmt(lowest_hop_height(s)) + " m at gravity " +
          fmt(s.gravity) + " m/s^2 (a longer step can pass over a whole flight and miss its " +
          "touchdown)",
      "h_fixed " + fmt(solver.h_fixed) + " s (" + std::string(ode::to_string(solver.method)) + ")"};
}

}  // namespace pronk::reduced
