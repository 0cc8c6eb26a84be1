// What a robot run may ask for, whatever its model (impulse, pulse, the full model): how
// many records it holds in memory (trajectory samples, stride records) and how long a
// fixed step may be and still see every flight. The scene loader refuses a scene past a
// limit (exit 2, with the numbers); the simulators check again for scenes made or changed
// in code (a study's bound parameters and scenarios, a map's model): past a memory limit
// they throw std::invalid_argument, a fixed step too long ends the run `diverged` at t = 0.
#pragma once

#include <optional>
#include <string>

#include "sim/ode/solver.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::reduced {

/// Most trajectory samples one run holds (duration / sample_interval), as mechanism scenes.
inline constexpr double kMaxSamples = 1e7;
/// Most stride records one run holds (max_strides).
inline constexpr long kMaxStrides = 10000000;

/// A limit a scene breaks, with the numbers.
struct LimitBreach {
  std::string field;     ///< the scene key: "sample_interval", "max_strides" or "h_fixed"
  std::string expected;  ///< the limit
  std::string found;     ///< what the scene asks
  /// One line for a run's reason or an exception: "<found>: expected <expected>".
  std::string reason() const { return found + ": expected " + expected; }
};

/// Trajectory samples a run of `sim` records when it runs its whole duration:
/// duration / sample_interval.
double trajectory_samples(const scene::Simulation& sim);

/// The memory limits: trajectory samples (when `trajectory`, the run records them) and
/// stride records (when `strides`).
std::optional<LimitBreach> memory_limit_breach(const scene::Simulation& sim, bool trajectory,
                                               bool strides);

/// memory_limit_breach as an exception: std::invalid_argument("simulation.<field>: <reason>").
void require_memory_limits(const scene::Simulation& sim, bool trajectory, bool strides);

/// The longest fixed step [s] that still sees every flight: the rise time to the apex of the
/// lowest hop height the scene asks for, sqrt(2 h / g), half its flight. A step longer than a
/// flight can start at a liftoff and end below the touchdown height with no sign change of
/// the touchdown event in between (the flight skipped); half the flight leaves a margin for
/// flights shorter than asked. Infinite without gravity (no flight ends).
double max_fixed_step(const scene::Scene& s);

/// The fixed-step rule for `solver` (euler, rk2, rk4, verlet; the adaptive methods pass).
std::optional<LimitBreach> fixed_step_breach(const scene::Scene& s,
                                             const ode::SolverOptions& solver);

}  // namespace pronk::reduced
