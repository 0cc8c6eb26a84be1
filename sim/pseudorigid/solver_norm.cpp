#include "sim/pseudorigid/solver_norm.hpp"

#include <utility>

namespace pronk::pseudorigid {

ode::ErrorNorm solver_norm(const Mechanism& m, const MechanismSystem& sys, bool mass_scaled) {
  if (m.simulation.error_norm == ErrorNorm::kBody) {
    return ode::ErrorNorm::custom(
        [&sys](const ode::Vec& err, const ode::Vec& y0, const ode::Vec& y1, double rtol,
               double atol) { return sys.error_norm(err, y0, y1, rtol, atol); });
  }
  if (!mass_scaled) return {};
  ode::Vec scale = ode::Vec::Ones(sys.dimension());
  for (size_t j = 0; j < m.masses.size(); ++j) {
    const int dummy_of = m.masses[j].dummy_of;
    const double s = dummy_of >= 0 ? 0.25 * m.bodies[dummy_of].mass : m.masses[j].mass;
    scale.segment<3>(6 * j).setOnes();
    scale.segment<3>(6 * j + 3).setConstant(s);
  }
  for (int b = 0; b < static_cast<int>(m.bodies.size()); ++b) {
    const int r = m.rotation_state(b);
    if (r < 0) continue;
    scale.segment<4>(r).setOnes();
    scale.segment<3>(r + 4).setConstant(m.bodies[b].principal_moments.minCoeff());
  }
  return ode::ErrorNorm::scaled(std::move(scale));
}

}  // namespace pronk::pseudorigid
