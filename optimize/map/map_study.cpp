#include "optimize/map/map_study.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/load/json_reader.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/study.hpp"
#include "sim/robot/pseudo_rigid_robot.hpp"
#include "sim/scene/mujoco_scene.hpp"
#include "sim/scene/robot_scaling.hpp"
#include "sim/scene/scene.hpp"

namespace pronk::optimize::map {

using nlohmann::json;

namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr long kMaxValues = 10000;
constexpr long kMaxCells = 1000000;

// A [lo, hi] disturbance range with 0 <= lo <= hi, scaled.
void range(io::JsonReader& r, const std::string& key, double scale, double* lo, double* hi) {
  if (!r.has(key)) {
    r.optional(key);
    return;
  }
  const Eigen::VectorXd v = r.vector(key, 2, 0.0, 1e6);
  if (v[0] > v[1]) throw r.error(key, "[lo, hi] with lo <= hi", "lo > hi");
  *lo = v[0] * scale;
  *hi = v[1] * scale;
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string fmt12(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.12g", v);
  return b;
}

// "range" [lo, hi] with "count" points, linear or logarithmic spacing.
void parse_axis_range(io::JsonReader& r, MapAxis& a, double lo_allowed, double hi_allowed) {
  r.optional("values");
  const Eigen::VectorXd rg = r.vector("range", 2, lo_allowed, hi_allowed);
  const long n = r.integer_or("count", 2, 1, kMaxValues);
  if (n >= 2 && !(rg[0] < rg[1]))
    throw r.error("range", "[lo, hi] with lo < hi", "[" + fmt(rg[0]) + ", " + fmt(rg[1]) + "]");
  if (n == 1 && rg[0] != rg[1])
    throw r.error("range", "lo == hi when count is 1", "[" + fmt(rg[0]) + ", " + fmt(rg[1]) + "]");
  if (a.log_scale && rg[0] <= 0.0)
    throw r.error("range", "lo > 0 for \"scale\": \"log\"", fmt(rg[0]));
  a.values.resize(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    a.values[static_cast<size_t>(i)] =
        a.log_scale ? std::exp(std::log(rg[0]) + t * (std::log(rg[1]) - std::log(rg[0])))
                    : rg[0] + t * (rg[1] - rg[0]);
  }
  // Rounded to 12 significant digits (0.15, not 0.15000000000000002), exact end points.
  for (double& x : a.values) x = std::stod(fmt12(x));
  a.values.front() = rg[0];
  a.values.back() = rg[1];
  for (size_t i = 1; i < a.values.size(); ++i)
    if (!(a.values[i] > a.values[i - 1]))
      throw r.error("count", "few enough points for distinct values (12 digits)",
                    std::to_string(n));
}

// The axis kind; a pointer axis's pointer (checked against the scene), or the bounds
// [*lo, *hi] of the values of the other kinds.
void parse_axis_kind(io::JsonReader& r, const std::string& kind, const json& scene_doc, MapAxis& a,
                     double* lo, double* hi) {
  if (kind == "pointer") {
    a.kind = AxisKind::kPointer;
    a.pointer = r.string_or("pointer", "");
    const json* target = io::find_pointer(scene_doc, a.pointer);
    if (a.pointer.empty() || target == nullptr || !target->is_number()) {
      throw r.error("pointer", "a pointer to a number of the resolved scene",
                    "\"" + a.pointer + "\"" +
                        (a.pointer.empty() || target == nullptr
                             ? " (no such value" + io::resolved_pointer_hint(a.pointer) + ")"
                             : " (" + io::describe(*target) + ")"));
    }
  } else if (kind == "duty_cycle") {
    a.kind = AxisKind::kDutyCycle;
    *lo = 1e-4;
    *hi = 0.95;
  } else if (kind == "tilt_deg") {
    a.kind = AxisKind::kTilt;
    *lo = -179;
    *hi = 179;
  } else if (kind == "lateral_offset") {
    a.kind = AxisKind::kLateralOffset;
    *lo = -100;
    *hi = 100;
  } else if (kind == "velocity_kick") {
    a.kind = AxisKind::kVelocityKick;
    *lo = -100;
    *hi = 100;
  } else {
    a.kind = AxisKind::kDisturbanceDirection;
    *lo = -360;
    *hi = 360;
  }
}

// "values": a strictly increasing list within [lo, hi].
void parse_axis_values(io::JsonReader& r, const json& node, MapAxis& a, double lo, double hi) {
  r.optional("count");
  const json& v = node.at("values");
  if (!v.is_array() || v.empty() || static_cast<long>(v.size()) > kMaxValues)
    throw r.error("values", "a non-empty array of numbers", io::describe(v));
  const Eigen::VectorXd vv = r.vector("values", static_cast<int>(v.size()), lo, hi);
  a.values.assign(vv.data(), vv.data() + vv.size());
  for (size_t i = 1; i < a.values.size(); ++i) {
    if (!(a.values[i] > a.values[i - 1])) {
      throw io::InputError(r.file(), r.pointer_of("values") + "/" + std::to_string(i),
                           "strictly increasing values",
                           fmt(a.values[i]) + " after " + fmt(a.values[i - 1]));
    }
  }
  if (a.log_scale && a.values.front() <= 0.0)
    throw r.error("values", "values > 0 for \"scale\": \"log\"", fmt(a.values.front()));
}

MapAxis parse_axis(io::JsonReader r, const json& node, const json& scene_doc) {
  MapAxis a;
  const std::string kind = r.choice_or("kind", "",
                                       {"pointer", "duty_cycle", "tilt_deg", "lateral_offset",
                                        "velocity_kick", "disturbance_direction_deg"});
  double lo = -1e12, hi = 1e12;
  parse_axis_kind(r, kind, scene_doc, a, &lo, &hi);
  if (a.kind == AxisKind::kTilt) {
    const Eigen::Vector3d ax = r.vec3_or("axis", Eigen::Vector3d(1, 0, 0));
    if (!(ax.norm() > 1e-12)) throw r.error("axis", "a non-zero rotation axis", "a zero vector");
    a.tilt_axis = ax.normalized();
  }
  if (a.kind == AxisKind::kVelocityKick)
    a.direction_deg = r.number_or("direction_deg", 90, -360, 360);
  if (a.kind == AxisKind::kDisturbanceDirection)
    a.magnitude = r.number_or("magnitude", 0.0, 0.0, 100.0);
  // Keys of other kinds are errors, not silently ignored.
  const std::pair<const char*, AxisKind> own[] = {{"pointer", AxisKind::kPointer},
                                                  {"axis", AxisKind::kTilt},
                                                  {"direction_deg", AxisKind::kVelocityKick},
                                                  {"magnitude", AxisKind::kDisturbanceDirection}};
  for (const auto& [key, owner] : own) {
    if (a.kind != owner && r.has(key)) {
      throw r.error(key,
                    "no \"" + std::string(key) + "\" on a \"" + kind + "\" axis (only on \"" +
                        std::string(to_string(owner)) + "\")",
                    "\"" + std::string(key) + "\"");
    }
  }
  a.name = r.string_or("name", kind == "pointer" ? a.pointer : kind);
  if (a.name.empty() || a.name.find_first_of(",\"\n") != std::string::npos)
    throw r.error("name", "a non-empty name without commas or quotes", "\"" + a.name + "\"");
  // Values: a list or a range.
  const std::string scale = r.choice_or("scale", "linear", {"linear", "log"});
  a.log_scale = scale == "log";
  const bool has_values = r.has("values"), has_range = r.has("range");
  if (has_values == has_range) {
    throw r.error("values", "exactly one of \"values\" (a list) or \"range\" with \"count\"",
                  has_values ? "both" : "neither");
  }
  if (has_values) {
    parse_axis_values(r, node, a, lo, hi);
  } else {
    parse_axis_range(r, a, lo, hi);
  }
  r.finish();
  return a;
}

scene::ModelKind model_of(const std::string& file, const std::string& pointer, const json& v) {
  const auto kind = v.is_string() ? scene::model_kind(v.get<std::string>()) : std::nullopt;
  if (kind && (*kind != scene::ModelKind::kMujoco || scene::mujoco_available())) return *kind;
  throw io::InputError(file, pointer, scene::model_names_expected(), io::describe(v));
}

// The full model must be able to build the robot of `s` (the scene's "pseudo_rigid" settings).
void check_robot(const scene::Scene& s, const std::string& file, const std::string& pointer,
                 const std::string& what) {
  try {
    robot::build_robot(s);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(file, pointer, what, e.what());
  }
}

}  // namespace

std::string_view to_string(AxisKind k) {
  switch (k) {
    case AxisKind::kPointer:
      return "pointer";
    case AxisKind::kDutyCycle:
      return "duty_cycle";
    case AxisKind::kTilt:
      return "tilt_deg";
    case AxisKind::kLateralOffset:
      return "lateral_offset";
    case AxisKind::kVelocityKick:
      return "velocity_kick";
    case AxisKind::kDisturbanceDirection:
      return "disturbance_direction_deg";
  }
  return "?";
}

std::string MapAxis::unit() const {
  switch (kind) {
    case AxisKind::kPointer:
      return "";
    case AxisKind::kDutyCycle:
      return "-";
    case AxisKind::kTilt:
    case AxisKind::kDisturbanceDirection:
      return "deg";
    case AxisKind::kLateralOffset:
      return "m";
    case AxisKind::kVelocityKick:
      return "m/s";
  }
  return "";
}

double pulse_duration_for_duty(const scene::Scene& s, double duty) {
  const double flight = 2.0 * std::sqrt(2.0 * s.controller.hop_height / s.gravity);
  return duty * flight / (1.0 - duty);
}

DutySetting duty_setting(const scene::Scene& s) {
  const std::vector<std::string> unused = io::unused_settings(s);
  auto is_unused = [&unused](const char* p) {
    return std::find(unused.begin(), unused.end(), p) != unused.end();
  };
  if (!is_unused("/pulse/duration")) return DutySetting::kPulseDuration;
  if (scene::is_full_model(s.model) && s.pseudo_rigid.legs == scene::PseudoRigid::Legs::kSpring &&
      !is_unused("/pseudo_rigid/leg_stiffness"))
    return DutySetting::kLegStiffness;
  return DutySetting::kNone;
}

double leg_stiffness_for_duty(const scene::Scene& s, double duty) {
  return scene::leg_stiffness_for_stance(s, pulse_duration_for_duty(s, duty));
}

void apply_duty(scene::Scene& s, double duty) {
  if (duty_setting(s) == DutySetting::kLegStiffness) {
    s.pseudo_rigid.leg_stiffness = leg_stiffness_for_duty(s, duty);
  } else {
    s.pulse.duration = pulse_duration_for_duty(s, duty);
  }
}

namespace {

// The scene: a path (relative to the study; a design.json gives its resolved scene) or an
// inline object, plus overrides. Sets st->scene_file; returns the scene document.
json map_study_scene_doc(io::JsonReader& r, const json& doc, const std::string& file,
                         const std::string& base_dir, MapStudy* st) {
  if (!r.has("scene"))
    throw r.error("scene", "a scene file path, a design.json path or an inline scene", "nothing");
  const json& sv = doc.at("scene");
  r.optional("scene");
  json scene_doc;
  st->scene_file = file + "#/scene";
  if (sv.is_string()) {
    std::filesystem::path p(sv.get<std::string>());
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    st->scene_file = p.lexically_normal().string();
    scene_doc = io::read_json_file(st->scene_file);
    if (io::holds(scene_doc, "type", "pronk_design")) {
      if (!scene_doc.contains("scene") || !scene_doc.at("scene").is_object())
        throw io::InputError(st->scene_file, "/scene", "the design's resolved scene", "nothing");
      scene_doc = json(scene_doc.at("scene"));
      st->scene_file += "#/scene";
    }
  } else if (sv.is_object()) {
    scene_doc = sv;
  } else {
    throw r.error("scene", "a scene file path, a design.json path or an inline scene",
                  io::describe(sv));
  }
  apply_study_scene_overrides(r, doc, file, &scene_doc);
  return scene_doc;
}

std::vector<scene::ModelKind> map_study_models(io::JsonReader& r, const json& doc,
                                               const std::string& file) {
  std::vector<scene::ModelKind> models;
  if (r.has("models")) {
    const json& m = doc.at("models");
    r.optional("models");
    if (!m.is_array() || m.empty() || m.size() > 2)
      throw r.error("models", "an array of one or two of \"impulse\", \"pulse\", \"pseudo_rigid\"",
                    io::describe(m));
    for (size_t i = 0; i < m.size(); ++i) {
      models.push_back(model_of(file, "/models/" + std::to_string(i), m[i]));
    }
    if (models.size() == 2 && models[0] == models[1])
      throw r.error("models", "two different models", "the same model twice");
  } else {
    r.optional("models");
    models = {scene::ModelKind::kImpulse, scene::ModelKind::kPulse};
  }
  return models;
}

// The checks of each axis against the scene and the other axes.
void check_map_study_axes(const io::JsonReader& r, const std::string& file, const MapStudy& st) {
  if (st.axes.size() == 2 && st.axes[0].name == st.axes[1].name)
    throw io::InputError(file, "/axes/1/name", "a name different from axis 0's",
                         "\"" + st.axes[1].name + "\"");
  if (st.cells() > kMaxCells)
    throw r.error("axes", "at most " + std::to_string(kMaxCells) + " cells",
                  std::to_string(st.cells()));
  for (size_t i = 0; i < st.axes.size(); ++i) {
    const MapAxis& a = st.axes[i];
    if (a.kind == AxisKind::kDutyCycle && st.base_scene.pulse.mode != scene::PulseMode::kDuration) {
      throw io::InputError(st.scene_file, "/pulse/mode",
                           "\"duration\" (axis " + std::to_string(i) + " sets the pulse duration)",
                           "\"max_force\"");
    }
    // A duty axis sets the pulse duration, or the leg stiffness where the model times the
    // thrust itself (apply_duty); a model that uses neither would give a flat, silently
    // meaningless row.
    for (const scene::ModelKind m : st.models) {
      if (a.kind != AxisKind::kDutyCycle) break;
      scene::Scene s = st.base_scene;
      s.model = m;
      if (duty_setting(s) == DutySetting::kNone) {
        throw io::InputError(file, "/axes/" + std::to_string(i) + "/kind",
                             "an axis every model uses (the " + std::string(to_string(m)) +
                                 " model ignores /pulse/duration and the leg stiffness)",
                             "\"duty_cycle\"");
      }
    }
    if (a.kind == AxisKind::kDisturbanceDirection) {
      const bool has_kick = std::any_of(st.axes.begin(), st.axes.end(), [](const MapAxis& b) {
        return b.kind == AxisKind::kVelocityKick;
      });
      if (!has_kick && !(a.magnitude > 0.0))
        throw io::InputError(file, "/axes/" + std::to_string(i) + "/magnitude",
                             "a kick size > 0 [m/s] (no velocity_kick axis)", fmt(a.magnitude));
    }
  }
  if (st.axes.size() == 2 && st.axes[0].kind != AxisKind::kPointer &&
      st.axes[0].kind == st.axes[1].kind)
    throw io::InputError(file, "/axes/1/kind", "a kind different from axis 0's",
                         "\"" + std::string(to_string(st.axes[1].kind)) + "\"");
  if (st.axes.size() == 2 && st.axes[0].kind == AxisKind::kPointer &&
      st.axes[1].kind == AxisKind::kPointer && st.axes[0].pointer == st.axes[1].pointer)
    throw io::InputError(file, "/axes/1/pointer", "a pointer different from axis 0's",
                         "\"" + st.axes[1].pointer + "\"");
}

void parse_map_study_axes(io::JsonReader& r, const json& doc, const std::string& file,
                          MapStudy* st) {
  if (!r.has("axes")) throw r.error("axes", "an array of one or two axes", "nothing");
  const json& axes_node = doc.at("axes");
  if (!axes_node.is_array() || axes_node.empty() || axes_node.size() > 2)
    throw r.error("axes", "an array of one or two axes", io::describe(axes_node));
  auto readers = r.object_array("axes");
  for (size_t i = 0; i < readers.size(); ++i)
    st->axes.push_back(parse_axis(readers[i], axes_node[i], st->scene_doc));
  check_map_study_axes(r, file, *st);
}

void parse_map_study_trials(io::JsonReader t, MapStudy* st) {
  st->trials.count = t.integer_or("count", 16, 1, 100000);
  st->trials.seed = static_cast<std::uint64_t>(t.integer_or("seed", 1, 0, 9007199254740991L));
  st->trial_set.duration = t.number_or("duration", 12.0, 1e-3, 1e6);
  st->trial_set.strides = t.integer_or("strides", 0, 0, 10000000);  // reduced::kMaxStrides
  auto& tr = st->trials;
  range(t, "tilt_deg", kDeg, &tr.tilt_lo, &tr.tilt_hi);
  range(t, "offset", 1.0, &tr.offset_lo, &tr.offset_hi);
  range(t, "lateral_offset", 1.0, &tr.lateral_lo, &tr.lateral_hi);
  range(t, "velocity_kick", 1.0, &tr.kick_lo, &tr.kick_hi);
  range(t, "yaw_deg", kDeg, &tr.yaw_lo, &tr.yaw_hi);
  range(t, "angular_velocity", 1.0, &tr.spin_lo, &tr.spin_hi);
  const std::string seeding = t.choice_or("seeding", "row", {"row", "cell"});
  st->seeding = seeding == "cell" ? Seeding::kCell : Seeding::kRow;
  t.finish();
}

// "stabilized", "stability" and "boundary" (the resolution in axis-0 units: default 1/8 of
// the smallest spacing).
void parse_map_study_criteria(io::JsonReader& r, MapStudy* st) {
  if (r.has("stabilized")) {
    io::JsonReader s = r.object("stabilized");
    st->stabilized.settle.position_error = s.positive_or("position_error", 0.01);
    st->stabilized.settle.tilt = s.positive_or("tilt_deg", 1.0) * kDeg;
    st->stabilized.settle.apex_error = s.positive_or("apex_error", 0.005);
    st->stabilized.within_strides = s.integer_or("within_strides", 30, 0, 100000000);
    st->stabilized.hold_strides = s.integer_or("hold_strides", 3, 1, 100000000);
    s.finish();
  } else {
    r.optional("stabilized");
  }
  st->stability = r.boolean_or("stability", true);
  const auto& v = st->axes[0].values;
  double spacing = 0.0;
  for (size_t i = 1; i < v.size(); ++i)
    spacing = i == 1 ? v[1] - v[0] : std::min(spacing, v[i] - v[i - 1]);
  if (r.has("boundary")) {
    io::JsonReader b = r.object("boundary");
    st->resolution = b.positive_or("resolution", spacing > 0 ? spacing / 8 : 1e-3);
    st->max_bisection_steps = static_cast<int>(b.integer_or("max_steps", 40, 0, 200));
    b.finish();
  } else {
    r.optional("boundary");
    st->resolution = spacing > 0 ? spacing / 8 : 1e-3;
  }
}

// Every pointer-axis value must make a valid scene; errors name the axis value.
void check_map_study_pointer_values(const MapStudy& st, const std::string& file, bool full_model) {
  for (size_t i = 0; i < st.axes.size(); ++i) {
    const MapAxis& a = st.axes[i];
    if (a.kind != AxisKind::kPointer) continue;
    for (size_t k = 0; k < a.values.size(); ++k) {
      json d = st.scene_doc;
      d[json::json_pointer(a.pointer)] = a.values[k];
      const std::string where = "/axes/" + std::to_string(i) + "/values/" + std::to_string(k);
      scene::Scene s;
      try {
        s = io::parse_scene(d, st.scene_file);
      } catch (const io::InputError& e) {
        throw io::InputError(
            file, where,
            "a value that makes a valid scene (" + e.pointer() + ": " + e.expected() + ")",
            e.found());
      }
      if (full_model)
        check_robot(s, file, where, "a value that makes a robot the full model can build");
    }
  }
}

}  // namespace

MapStudy parse_map_study(const json& doc, const std::string& file, const std::string& base_dir) {
  MapStudy st;
  st.file = file;
  st.document = doc;
  io::JsonReader r(doc, file, "");
  const std::string kind = r.string_or("kind", "");
  if (kind != "map") {
    throw r.error("kind", "\"map\" (a robustness-map study)",
                  doc.contains("kind") ? io::describe(doc.at("kind")) : "nothing");
  }
  st.name = r.path_name_or("name", "");  // the default output directory results/<name>
  r.string_or("description", "");
  const json scene_doc = map_study_scene_doc(r, doc, file, base_dir, &st);
  st.base_scene = io::parse_scene(scene_doc, st.scene_file);
  st.scene_doc = io::scene_to_json(st.base_scene);
  st.models = map_study_models(r, doc, file);
  const bool full_model = std::any_of(st.models.begin(), st.models.end(),
                                      [](auto m) { return scene::is_full_model(m); });
  if (full_model)
    check_robot(st.base_scene, st.scene_file, "/pseudo_rigid", "a robot the full model can build");
  // (each cell's model is set here, past the scene loader's check of "model": "mujoco")
  if (std::find(st.models.begin(), st.models.end(), scene::ModelKind::kMujoco) != st.models.end()) {
    if (const auto m = scene::mujoco_refusal(st.base_scene)) {
      throw io::InputError(st.scene_file, m->pointer, m->expected, m->found);
    }
  }
  parse_map_study_axes(r, doc, file, &st);
  parse_map_study_trials(r.object("trials"), &st);
  parse_map_study_criteria(r, &st);
  st.output_dir = r.string_or("output", "results/" + st.name);
  r.finish();
  check_map_study_pointer_values(st, file, full_model);
  st.hash = fnv1a_hex(doc.dump() + "\n" + st.scene_doc.dump());
  return st;
}

MapStudy load_map_study(const std::string& path, const std::vector<std::string>& overrides) {
  json doc = io::read_json_file(path);
  for (const auto& o : overrides) io::apply_override(doc, o);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_map_study(doc, path, dir.empty() ? "." : dir);
}

}  // namespace pronk::optimize::map
