// make_stepper(): dispatch on the method to the concrete steppers.
#include <utility>

#include "sim/ode/solver.hpp"
#include "sim/ode/steppers.hpp"

namespace pronk::ode {

std::unique_ptr<Stepper> make_stepper(const SolverOptions& options, int n, ErrorNorm norm) {
  if (options.method == Method::kDopri5) {
    return detail::make_dopri5_stepper(options, n, std::move(norm));
  }
  if (options.method == Method::kRodas4) {
    return detail::make_rodas4_stepper(options, n, std::move(norm));
  }
  if (options.method == Method::kRadau5) {
    return detail::make_radau5_stepper(options, n, std::move(norm));
  }
  if (options.method == Method::kCvodeBdf) {
    return detail::make_cvode_stepper(options, n, std::move(norm));
  }
  if (options.method == Method::kVerlet) return detail::make_verlet_stepper(options, n);
  return detail::make_explicit_rk_stepper(options, n);
}

}  // namespace pronk::ode
