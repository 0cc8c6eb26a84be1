#include "sim/scene/scene.hpp"

namespace pronk::scene {

std::string_view to_string(ModelKind k) {
  switch (k) {
    case ModelKind::kImpulse:
      return "impulse";
    case ModelKind::kPulse:
      return "pulse";
    case ModelKind::kPseudoRigid:
      return "pseudo_rigid";
  }
  return "?";
}

void seed_gains(const Body& body, Vec6* kp, Vec6* kd) {
  const double m = body.mass;
  const Vec3 I = body.inertia.diagonal();
  *kp << m, m, 0.0, I.x(), I.y(), I.z();
  *kd << 1.5 * m, 1.5 * m, m, 1.5 * I.x(), 1.5 * I.y(), 1.5 * I.z();
}

}  // namespace pronk::scene
