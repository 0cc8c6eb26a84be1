// Scenarios: the initial conditions and disturbances a design is judged on.
// Explicit ones from the study, and seeded random samples whose every draw
// depends only on (seed, index), so results never depend on scheduling.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "optimize/perturbation.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize {

struct Scenario {
  std::string name;
  Eigen::Vector3d position_offset = Eigen::Vector3d::Zero();  ///< added to the initial CoM [m]
  Eigen::Vector3d velocity_kick = Eigen::Vector3d::Zero();  ///< added to the initial velocity [m/s]
  Eigen::Vector3d tilt =
      Eigen::Vector3d::Zero();  ///< 1-2-3 angles composed onto the initial attitude [rad]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< added body rates [rad/s]
  std::vector<scene::Disturbance> disturbances;                ///< added to the scene's
  double duration = 0.0;  ///< simulated time [s]; 0: the set's default
  long strides = 0;       ///< stop after this many strides; 0: the set's default
  /// The robot's own numbers drawn for this scenario (the plant; the controller keeps the
  /// nominal ones). Empty: the nominal robot.
  std::vector<PlantDraw> plant;
};

/// Ranges of the random disturbances: a magnitude drawn uniformly in [lo, hi]
/// with a uniformly random horizontal direction (3-D for angular velocity).
struct RandomScenarios {
  long count = 0;
  std::uint64_t seed = 1;
  double tilt_lo = 0, tilt_hi = 0;         ///< tilt about a random horizontal axis [rad]
  double offset_lo = 0, offset_hi = 0;     ///< horizontal CoM offset [m]
  double lateral_lo = 0, lateral_hi = 0;   ///< offset along y only, random sign [m]
  double kick_lo = 0, kick_hi = 0;         ///< horizontal velocity kick [m/s]
  double yaw_lo = 0, yaw_hi = 0;           ///< yaw error, random sign [rad]
  double spin_lo = 0, spin_hi = 0;         ///< angular velocity, random direction [rad/s]
  std::vector<PlantPerturbation> perturb;  ///< the robot's numbers, each drawn on its own stream
};

struct ScenarioSet {
  std::vector<Scenario> scenarios;  ///< explicit ones first, then the random samples
  double duration = 5.0;            ///< default simulated time [s]
  long strides = 0;                 ///< default stride limit; 0 = none
  /// With robot perturbations: also evaluate the set on the nominal robot, to report both
  /// (a study's validation set; "compare_nominal").
  bool compare_nominal = true;
};

/// True when some scenario of the set perturbs the robot.
bool perturbs_robot(const ScenarioSet& set);

/// The same scenarios on the nominal robot (the robot perturbations dropped, the starts kept).
ScenarioSet with_nominal_robot(const ScenarioSet& set);

/// Random sample number `index` of `spec` (depends only on spec.seed and index).
Scenario sample_scenario(const RandomScenarios& spec, long index);

/// Appends spec.count samples to the set.
void add_random_scenarios(const RandomScenarios& spec, ScenarioSet& set);

/// The scene with the scenario applied: the robot perturbed (its controller keeping the
/// nominal numbers), then the start and the disturbances.
scene::Scene apply_scenario(const scene::Scene& base, const Scenario& s, const ScenarioSet& set);

/// A small counter-based generator (SplitMix64): portable, bit-identical everywhere.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t state_;
};

/// Mixes two numbers into one seed (for per-trial seeds).
std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b);

}  // namespace pronk::optimize
