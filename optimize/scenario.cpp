#include "optimize/scenario.hpp"

#include <algorithm>
#include <cmath>

#include "sim/math/rotation.hpp"

namespace pronk::optimize {

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b) {
  SplitMix64 g(a ^ (0x632be59bd9b4e019ULL + (b << 6) + (b >> 2)));
  g.next();
  return g.next() ^ b;
}

Scenario sample_scenario(const RandomScenarios& spec, long index) {
  const std::uint64_t seed = mix_seed(spec.seed, static_cast<std::uint64_t>(index));
  SplitMix64 g(seed);
  Scenario s;
  s.name = "random_" + std::to_string(index);
  auto horizontal = [&g]() {
    const double a = g.uniform(0.0, 2.0 * M_PI);
    return Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
  };
  auto sign = [&g]() { return g.uniform() < 0.5 ? -1.0 : 1.0; };
  // Always draw every quantity, so adding a range never shifts the others.
  const Eigen::Vector3d tilt_axis = horizontal();
  const double tilt = g.uniform(spec.tilt_lo, spec.tilt_hi);
  const Eigen::Vector3d offset_dir = horizontal();
  const double offset = g.uniform(spec.offset_lo, spec.offset_hi);
  const double lateral = sign() * g.uniform(spec.lateral_lo, spec.lateral_hi);
  const Eigen::Vector3d kick_dir = horizontal();
  const double kick = g.uniform(spec.kick_lo, spec.kick_hi);
  const double yaw = sign() * g.uniform(spec.yaw_lo, spec.yaw_hi);
  const double z = g.uniform(-1.0, 1.0), phi = g.uniform(0.0, 2.0 * M_PI);
  const Eigen::Vector3d spin_dir(std::sqrt(1 - z * z) * std::cos(phi),
                                 std::sqrt(1 - z * z) * std::sin(phi), z);
  const double spin = g.uniform(spec.spin_lo, spec.spin_hi);
  // Tilt about a horizontal axis as 1-2-3 angles of the equivalent rotation.
  const math::Quat q(Eigen::AngleAxisd(tilt, tilt_axis));
  s.tilt = math::quat_to_euler(q * math::Quat(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())),
                               math::EulerSet::k123);
  s.position_offset = offset * offset_dir + Eigen::Vector3d(0.0, lateral, 0.0);
  s.velocity_kick = kick * kick_dir;
  s.angular_velocity = spin * spin_dir;
  for (size_t k = 0; k < spec.perturb.size(); ++k)
    s.plant.push_back(draw_perturbation(spec.perturb[k], seed, static_cast<long>(k)));
  return s;
}

void add_random_scenarios(const RandomScenarios& spec, ScenarioSet& set) {
  for (long i = 0; i < spec.count; ++i) set.scenarios.push_back(sample_scenario(spec, i));
}

bool perturbs_robot(const ScenarioSet& set) {
  return std::any_of(set.scenarios.begin(), set.scenarios.end(),
                     [](const Scenario& s) { return !s.plant.empty(); });
}

ScenarioSet with_nominal_robot(const ScenarioSet& set) {
  ScenarioSet nominal = set;
  for (Scenario& s : nominal.scenarios) s.plant.clear();
  return nominal;
}

scene::Scene apply_scenario(const scene::Scene& base, const Scenario& s, const ScenarioSet& set) {
  scene::Scene sc = s.plant.empty() ? base : perturbed_scene(base, s.plant);
  sc.initial.position += s.position_offset;
  sc.initial.velocity += s.velocity_kick;
  sc.initial.attitude =
      (base.initial.attitude * math::euler_to_quat(s.tilt, math::EulerSet::k123)).normalized();
  sc.initial.angular_velocity += s.angular_velocity;
  for (const auto& d : s.disturbances) sc.disturbances.push_back(d);
  std::stable_sort(sc.disturbances.begin(), sc.disturbances.end(),
                   [](const auto& a, const auto& b) { return a.time < b.time; });
  sc.simulation.duration = s.duration > 0 ? s.duration : set.duration;
  const long strides = s.strides > 0 ? s.strides : set.strides;
  if (strides > 0) sc.simulation.max_strides = strides;
  return sc;
}

}  // namespace pronk::optimize
