#include "sim/scene/mujoco_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pronk::scene {

namespace {

std::string number_text(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

}  // namespace

std::optional<MujocoRefusal> mujoco_refusal(const Scene& s) {
  if (s.legs.body_only) {
    return MujocoRefusal{"/legs/kind", "\"legged\" (MuJoCo runs the robot with its legs)",
                         "\"body_only\""};
  }
  if (s.pseudo_rigid.legs != PseudoRigid::Legs::kSpring) {
    return MujocoRefusal{"/pseudo_rigid/legs",
                         "\"spring\" (MuJoCo's legs are spring-damper slides with feet)",
                         "\"force\""};
  }
  if (s.pseudo_rigid.feet == PseudoRigid::Feet::kQuasiStatic) {
    return MujocoRefusal{"/pseudo_rigid/feet",
                         "\"mass\" (MuJoCo's feet are bodies on the legs' slide joints)",
                         "\"quasi_static\""};
  }
  if (!(s.pseudo_rigid.foot_mass > 0.0)) {
    return MujocoRefusal{"/pseudo_rigid/foot_mass", "a foot mass > 0 kg for MuJoCo's feet",
                         number_text(s.pseudo_rigid.foot_mass)};
  }
  const double flight = std::sqrt(2.0 * s.controller.hop_height / std::max(s.gravity, 1e-9));
  if (s.mujoco.timestep > 0.1 * flight) {
    return MujocoRefusal{
        "/mujoco/timestep",
        "a step below a tenth of the hop's fall time (" + number_text(0.1 * flight) + " s)",
        number_text(s.mujoco.timestep)};
  }
  return std::nullopt;
}

}  // namespace pronk::scene
