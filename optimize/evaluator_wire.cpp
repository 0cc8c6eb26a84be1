#include "optimize/evaluator_wire.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pronk::optimize {

namespace {

using nlohmann::json;

json wire_number(double v) {
  if (std::isfinite(v)) return v;
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

double number_from_wire(const json& j) {
  if (j.is_number()) return j.get<double>();
  const std::string s = j.get<std::string>();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  throw std::runtime_error("evaluator wire: not a number: " + s);
}

json wire_vec3(const Eigen::Vector3d& v) {
  return {wire_number(v.x()), wire_number(v.y()), wire_number(v.z())};
}

Eigen::Vector3d vec3_from_wire(const json& j) {
  return {number_from_wire(j.at(0)), number_from_wire(j.at(1)), number_from_wire(j.at(2))};
}

json scenario_to_wire(const Scenario& s) {
  json d = json::array();
  for (const auto& x : s.disturbances)
    d.push_back({wire_number(x.time), wire_vec3(x.linear_impulse), wire_vec3(x.angular_impulse)});
  json plant = json::array();  // the robot's drawn numbers, exact doubles
  for (const auto& x : s.plant) plant.push_back({x.pointer, x.relative, wire_number(x.value)});
  return {{"name", s.name},
          {"plant", plant},
          {"position_offset", wire_vec3(s.position_offset)},
          {"velocity_kick", wire_vec3(s.velocity_kick)},
          {"tilt", wire_vec3(s.tilt)},
          {"angular_velocity", wire_vec3(s.angular_velocity)},
          {"disturbances", d},
          {"duration", wire_number(s.duration)},
          {"strides", s.strides}};
}

Scenario scenario_from_wire(const json& j) {
  Scenario s;
  s.name = j.at("name").get<std::string>();
  for (const auto& x : j.at("plant")) {
    s.plant.push_back({x.at(0).get<std::string>(), x.at(1).get<bool>(), number_from_wire(x.at(2))});
  }
  s.position_offset = vec3_from_wire(j.at("position_offset"));
  s.velocity_kick = vec3_from_wire(j.at("velocity_kick"));
  s.tilt = vec3_from_wire(j.at("tilt"));
  s.angular_velocity = vec3_from_wire(j.at("angular_velocity"));
  for (const auto& d : j.at("disturbances")) {
    scene::Disturbance x;
    x.time = number_from_wire(d.at(0));
    x.linear_impulse = vec3_from_wire(d.at(1));
    x.angular_impulse = vec3_from_wire(d.at(2));
    s.disturbances.push_back(x);
  }
  s.duration = number_from_wire(j.at("duration"));
  s.strides = j.at("strides").get<long>();
  return s;
}

}  // namespace

json evaluator_config_to_wire(const EvaluatorConfig& c) {
  json params = json::array();
  for (const auto& p : c.parameters)
    params.push_back({{"name", p.name},
                      {"pointer", p.pointer},
                      {"lower", wire_number(p.lower)},
                      {"upper", wire_number(p.upper)},
                      {"log", p.log_scale},
                      {"initial", wire_number(p.initial)}});
  json scenarios = json::array();
  for (const auto& s : c.scenarios.scenarios) scenarios.push_back(scenario_to_wire(s));
  return {{"scene", c.scene_doc},
          {"scene_file", c.scene_file},
          {"parameters", params},
          {"scenarios", scenarios},
          {"duration", wire_number(c.scenarios.duration)},
          {"strides", c.scenarios.strides},
          {"stability", c.stability},
          {"fall_penalty", wire_number(c.fall_penalty)},
          {"failure_cost", wire_number(c.failure_cost)},
          {"settle",
           {wire_number(c.settle.position_error), wire_number(c.settle.tilt),
            wire_number(c.settle.apex_error)}}};
}

EvaluatorConfig evaluator_config_from_wire(const json& j) {
  try {
    EvaluatorConfig c;
    c.scene_doc = j.at("scene");
    c.scene_file = j.at("scene_file").get<std::string>();
    for (const auto& p : j.at("parameters")) {
      Parameter q;
      q.name = p.at("name").get<std::string>();
      q.pointer = p.at("pointer").get<std::string>();
      q.lower = number_from_wire(p.at("lower"));
      q.upper = number_from_wire(p.at("upper"));
      q.log_scale = p.at("log").get<bool>();
      q.initial = number_from_wire(p.at("initial"));
      c.parameters.push_back(q);
    }
    for (const auto& s : j.at("scenarios")) c.scenarios.scenarios.push_back(scenario_from_wire(s));
    c.scenarios.duration = number_from_wire(j.at("duration"));
    c.scenarios.strides = j.at("strides").get<long>();
    c.stability = j.at("stability").get<bool>();
    c.fall_penalty = number_from_wire(j.at("fall_penalty"));
    c.failure_cost = number_from_wire(j.at("failure_cost"));
    c.settle.position_error = number_from_wire(j.at("settle").at(0));
    c.settle.tilt = number_from_wire(j.at("settle").at(1));
    c.settle.apex_error = number_from_wire(j.at("settle").at(2));
    c.threads = 1;
    return c;
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("evaluator wire: a malformed configuration: ") + e.what());
  }
}

json job_outcome_to_wire(const JobOutcome& o) {
  if (!o.error.empty()) return {{"error", o.error}};
  const StabilityEstimate& s = o.stability;
  json metrics = json::object();
  for (const auto& [k, v] : o.scenario.metrics) metrics[k] = wire_number(v);
  return {{"stability",
           {s.ok, s.reason, wire_number(s.spectral_radius), s.method, s.simulations, s.strides,
            wire_number(s.fit_residual)}},
          {"scenario",
           {o.scenario.name, o.scenario.status, o.scenario.reason, metrics, o.scenario.strides}}};
}

JobOutcome job_outcome_from_wire(const json& j) {
  JobOutcome o;
  try {
    if (j.contains("error")) {
      o.error = j.at("error").get<std::string>();
      return o;
    }
    const json& s = j.at("stability");
    o.stability.ok = s.at(0).get<bool>();
    o.stability.reason = s.at(1).get<std::string>();
    o.stability.spectral_radius = number_from_wire(s.at(2));
    o.stability.method = s.at(3).get<std::string>();
    o.stability.simulations = s.at(4).get<long>();
    o.stability.strides = s.at(5).get<long>();
    o.stability.fit_residual = number_from_wire(s.at(6));
    const json& c = j.at("scenario");
    o.scenario.name = c.at(0).get<std::string>();
    o.scenario.status = c.at(1).get<std::string>();
    o.scenario.reason = c.at(2).get<std::string>();
    for (const auto& [k, v] : c.at(3).items()) o.scenario.metrics[k] = number_from_wire(v);
    o.scenario.strides = c.at(4).get<long>();
  } catch (const json::exception& e) {
    o = JobOutcome{};
    o.error = std::string("a malformed job outcome: ") + e.what();
  }
  return o;
}

}  // namespace pronk::optimize
