#include "sim/scene/scene.hpp"

namespace pronk::scene {

const std::vector<std::string>& model_names() {
  static const std::vector<std::string> names = {"impulse", "pulse", "pseudo_rigid", "mujoco"};
  return names;
}

std::string_view to_string(ModelKind k) {
  const auto i = static_cast<size_t>(k);
  return i < model_names().size() ? std::string_view(model_names()[i]) : std::string_view("?");
}

std::optional<ModelKind> model_kind(std::string_view name) {
  const std::vector<std::string>& names = model_names();
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<ModelKind>(i);
  }
  return std::nullopt;
}

std::string model_names_expected() {
  std::vector<std::string> names = model_names();
  if (!mujoco_available()) std::erase(names, std::string(to_string(ModelKind::kMujoco)));
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + names[i] + "\"");
  }
  if (!mujoco_available()) {
    out +=
        " (this pronk was built without MuJoCo: install Debian's libmujoco-dev, e.g. with "
        "bash scripts/setup.sh, and rebuild for \"mujoco\")";
  }
  return out;
}

bool mujoco_available() {
#ifdef PRONK_HAVE_MUJOCO
  return true;
#else
  return false;
#endif
}

void seed_gains(const Body& body, Vec6* kp, Vec6* kd) {
  const double m = body.mass;
  const Vec3 I = body.inertia.diagonal();
  *kp << m, m, 0.0, I.x(), I.y(), I.z();
  *kd << 1.5 * m, 1.5 * m, m, 1.5 * I.x(), 1.5 * I.y(), 1.5 * I.z();
}

ControllerModel controller_model_of(const Scene& s) {
  if (s.controller_model) return *s.controller_model;
  ControllerModel c;
  c.body = s.body;
  c.pulse_max_force = s.pulse.max_force;
  c.leg_stiffness = s.pseudo_rigid.leg_stiffness;
  c.leg_damping = s.pseudo_rigid.leg_damping;
  c.actuator_max_force = s.pseudo_rigid.actuator_max_force;
  return c;
}

Scene controller_view(const Scene& s) {
  Scene v = s;
  if (!s.controller_model) return v;
  const ControllerModel& c = *s.controller_model;
  v.body = c.body;
  v.pulse.max_force = c.pulse_max_force;
  v.pseudo_rigid.leg_stiffness = c.leg_stiffness;
  v.pseudo_rigid.leg_damping = c.leg_damping;
  v.pseudo_rigid.actuator_max_force = c.actuator_max_force;
  v.controller_model.reset();
  return v;
}

}  // namespace pronk::scene
