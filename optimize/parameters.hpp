// Design parameters: named, bounded, optionally log-scaled numbers of the
// scene, bound by JSON Pointer. Drivers see every parameter mapped to [0, 1]
// (linear or logarithmic), so steps and tolerances mean the same for all.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::optimize {

struct Parameter {
  std::string name;
  std::string pointer;     ///< JSON Pointer into the scene document, e.g. "/controller/kp/3"
  double lower = 0.0;      ///< physical lower bound (same unit as the scene number)
  double upper = 1.0;      ///< physical upper bound
  bool log_scale = false;  ///< optimize log(value) (requires lower > 0)
  double initial = 0.0;    ///< starting value (default: the scene's own value)

  /// Physical value -> optimizer coordinate in [0, 1].
  double to_unit(double value) const;
  /// Optimizer coordinate (clamped to [0, 1]) -> physical value.
  double from_unit(double u) const;
};

/// Writes the physical values of `unit` (optimizer coordinates) into a copy of
/// the scene document. Cheap: one pointer write per parameter.
nlohmann::json bind_parameters(const nlohmann::json& scene_doc,
                               const std::vector<Parameter>& params,
                               const std::vector<double>& unit);

/// Physical values of optimizer coordinates.
std::vector<double> physical_values(const std::vector<Parameter>& params,
                                    const std::vector<double>& unit);

/// True when `pointer` is `prefix` or lies under it ("/pulse" covers "/pulse/duration").
bool pointer_under(const std::string& pointer, const std::string& prefix);

/// The setting of `unused` (io::unused_settings: what a model ignores) that covers `pointer`,
/// or nullptr: a number a study tunes or perturbs must be one its model uses.
const std::string* ignored_setting(const std::vector<std::string>& unused,
                                   const std::string& pointer);

}  // namespace pronk::optimize
