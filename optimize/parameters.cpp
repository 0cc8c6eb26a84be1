#include "optimize/parameters.hpp"

#include <algorithm>
#include <cmath>

namespace pronk::optimize {

double Parameter::to_unit(double value) const {
  double u = 0.0;
  if (log_scale) {
    u = (std::log(value) - std::log(lower)) / (std::log(upper) - std::log(lower));
  } else {
    u = (value - lower) / (upper - lower);
  }
  return std::clamp(u, 0.0, 1.0);
}

double Parameter::from_unit(double u) const {
  u = std::clamp(std::isfinite(u) ? u : 0.0, 0.0, 1.0);
  // Clamped: exp(log(lower)) can round a double below lower (and the same at upper), and a
  // value outside its own bounds is refused when the tuned design is read back.
  if (log_scale) {
    return std::clamp(std::exp(std::log(lower) + u * (std::log(upper) - std::log(lower))), lower,
                      upper);
  }
  return std::clamp(lower + u * (upper - lower), lower, upper);
}

std::vector<double> physical_values(const std::vector<Parameter>& params,
                                    const std::vector<double>& unit) {
  std::vector<double> out(params.size());
  for (size_t i = 0; i < params.size(); ++i) out[i] = params[i].from_unit(unit[i]);
  return out;
}

nlohmann::json bind_parameters(const nlohmann::json& scene_doc,
                               const std::vector<Parameter>& params,
                               const std::vector<double>& unit) {
  nlohmann::json doc = scene_doc;
  for (size_t i = 0; i < params.size(); ++i) {
    doc[nlohmann::json::json_pointer(params[i].pointer)] = params[i].from_unit(unit[i]);
  }
  return doc;
}

bool pointer_under(const std::string& pointer, const std::string& prefix) {
  return pointer == prefix ||
         (pointer.size() > prefix.size() && pointer.compare(0, prefix.size(), prefix) == 0 &&
          pointer[prefix.size()] == '/');
}

const std::string* ignored_setting(const std::vector<std::string>& unused,
                                   const std::string& pointer) {
  for (const std::string& u : unused)
    if (pointer_under(pointer, u)) return &u;
  return nullptr;
}

}  // namespace pronk::optimize
