#include "io/write/method_choice_output.hpp"

#include <string>

namespace pronk::io {

void add_method_choice(const pseudorigid::MethodChoice& c, double drift_relative,
                       nlohmann::json* summary) {
  nlohmann::json a = {{"method", std::string(ode::to_string(c.method))},
                      {"rule", c.rule},
                      {"accuracy", c.accuracy},
                      {"omega_max_rad_s", c.probe.omega_max},
                      {"omega_bound_rad_s", c.probe.omega_bound},
                      {"min_mass_kg", c.probe.min_mass},
                      {"contact", c.probe.contact},
                      {"dissipation", c.probe.dissipation},
                      {"energy_balance_drift_relative", drift_relative},
                      {"accuracy_met", drift_relative <= c.accuracy}};
  if (c.method == ode::Method::kVerlet) {
    a["h_fixed_s"] = c.h_fixed;
    if (c.h_flight > 0.0) a["h_flight_s"] = c.h_flight;
    a["energy_tol"] = c.energy_tol;
  } else {
    a["rtol"] = c.rtol;
    a["atol"] = c.atol;
  }
  a["reruns"] = c.reruns;
  if (c.reruns > 0) a["first_run_drift_relative"] = c.first_drift;
  (*summary)["method_choice"] = c.reason;
  (*summary)["auto"] = a;
}

}  // namespace pronk::io
