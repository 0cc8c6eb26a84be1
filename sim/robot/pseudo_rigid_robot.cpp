#include "sim/robot/pseudo_rigid_robot.hpp"

#include <sstream>
#include <stdexcept>

#include "sim/pseudorigid/builder.hpp"

namespace pronk::robot {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

/// The scene's body as the mechanism's body (four masses or one rigid body), with dummy hip
/// masses taken out of its mass and inertia; *offset: the main masses' centroid relative to
/// the CoM, body frame [m]. Adds it to r.mechanism and sets r.body.
pr::BodySpec add_robot_body(const scene::Scene& s, const std::vector<Vector3d>& hips, bool dummy,
                            bool rigid, RobotModel& r, Vector3d* offset_out) {
  const scene::PseudoRigid& p = s.pseudo_rigid;
  pr::Mechanism& m = r.mechanism;
  Vector3d offset = Vector3d::Zero();  // main-mass centroid relative to the CoM, body frame [m]
  // Dummy masses are part of the body: the four main masses carry the rest so the
  // total mass and inertia about the CoM stay those of the scene.
  pr::BodySpec b;
  b.name = "body";
  b.mass = s.body.mass;
  b.inertia = s.body.inertia;
  if (dummy) {
    const double md = p.dummy_ratio * s.body.mass;
    Vector3d first_moment = Vector3d::Zero();  // of the dummies about the CoM [kg m]
    for (const Vector3d& h : hips) {
      b.mass -= md;
      b.inertia -= md * (h.squaredNorm() * Matrix3d::Identity() - h * h.transpose());
      first_moment += md * h;
    }
    if (!(b.mass > 0.0)) {
      throw std::invalid_argument("dummy masses (" + std::to_string(hips.size()) + " x " +
                                  std::to_string(p.dummy_ratio) +
                                  " of the body mass) leave no mass for the body");
    }
    // The main masses' centroid sits at c so that the whole body's CoM stays at the
    // scene's; their inertia about c is what the dummies and the offset leave.
    offset = -first_moment / b.mass;
    b.inertia -=
        b.mass * (offset.squaredNorm() * Matrix3d::Identity() - offset * offset.transpose());
  }
  b.com = s.initial.position + s.initial.attitude.toRotationMatrix() * offset;
  b.attitude = s.initial.attitude.toRotationMatrix();
  b.omega = b.attitude * s.initial.angular_velocity;
  b.velocity = s.initial.velocity + b.omega.cross(b.attitude * offset);
  b.internal_stiffness = p.internal_stiffness;
  b.internal_damping = p.internal_damping;
  b.rigid = rigid;
  std::string err;
  r.body = pr::add_body(m, b, &err);
  if (r.body < 0) throw std::invalid_argument("body: " + err);
  *offset_out = offset;
  return b;
}

/// Leg i's foot mass, leg spring (with its damper) and slide on the body; hips without spring
/// legs get placeholders.
void add_robot_leg(const scene::Scene& s, size_t i, const Vector3d& hip, const Vector3d& offset,
                   bool dummy, const pr::BodySpec& b, RobotModel& r) {
  const scene::PseudoRigid& p = s.pseudo_rigid;
  pr::Mechanism& m = r.mechanism;
  const Matrix3d R = b.attitude;
  const std::string name = "leg" + std::to_string(i);
  const Vector3d h = hip - offset;  // relative to the main masses' centroid
  r.hip.push_back(hip);
  r.direction.push_back(-Vector3d::UnitZ());
  const pr::NodeRef ghost = pr::add_ghost_point(m, r.body, name + ".hip", h);
  r.hip_node.push_back(dummy ? pr::add_dummy_mass(m, r.body, name + ".hip_mass", h, p.dummy_ratio,
                                                  p.internal_stiffness, p.internal_damping)
                             : ghost);
  if (!r.spring_legs) {
    r.foot.push_back(-1);
    r.slide.push_back(-1);
    r.rest_length.push_back(0.0);
    r.leg_spring.push_back(-1);
    return;
  }
  // The foot touches the ground when the CoM of a level body is at legs.length.
  const double rest = s.legs.length + hip.z();
  if (!(rest > 0.0)) {
    throw std::invalid_argument("leg " + std::to_string(i) + ": hip z " + std::to_string(h.z()) +
                                " m leaves no leg below it for length " +
                                std::to_string(s.legs.length) + " m");
  }
  r.rest_length.push_back(rest);
  if (r.quasi_static_feet) {  // the feet are RobotSystem's
    r.foot.push_back(-1);
    r.slide.push_back(-1);
    r.leg_spring.push_back(-1);
    return;
  }
  const Vector3d arm = R * (h - rest * Vector3d::UnitZ());
  const pr::NodeRef foot =
      pr::add_mass(m, name + ".foot", p.foot_mass, b.com + arm, b.velocity + b.omega.cross(arm));
  r.foot.push_back(foot.index);
  pr::Connection c;
  c.name = name + ".spring";
  c.a = foot;
  c.b = r.hip_node.back();
  c.kind = pr::ConnectionClass::kLeg;
  c.stiffness = p.leg_stiffness;
  c.rest_length = rest;
  c.damping = p.leg_damping;
  r.leg_spring.push_back(static_cast<int>(m.connections.size()));
  m.connections.push_back(c);
  pr::Surface slide;
  slide.name = name + ".slide";
  slide.type = pr::SurfaceType::kLine;
  slide.body = r.body;
  slide.ghost = ghost.index;
  slide.direction = Vector3d::UnitZ();
  slide.nodes = {foot};
  slide.stiffness = p.internal_stiffness;
  slide.damping = p.internal_damping;
  r.slide.push_back(static_cast<int>(m.surfaces.size()));
  m.surfaces.push_back(slide);
}

/// The ground plane under the feet (contact spring and damper, regularised Coulomb friction).
void add_robot_ground(const scene::PseudoRigid& p, RobotModel& r) {
  pr::Mechanism& m = r.mechanism;
  pr::Surface ground;
  ground.name = "ground";
  ground.type = pr::SurfaceType::kPlane;
  ground.point = Vector3d::Zero();
  ground.direction = Vector3d::UnitZ();
  for (int f : r.foot) ground.nodes.push_back(pr::NodeRef{pr::NodeRef::Kind::kMass, f});
  ground.stiffness = p.contact_stiffness;
  ground.damping = p.contact_damping;
  ground.friction = p.friction;  // regularised Coulomb on the feet
  ground.slip_velocity = p.slip_velocity;
  r.ground = static_cast<int>(m.surfaces.size());
  m.surfaces.push_back(ground);
}

/// "auto" internal or contact stiffness: chosen from the mechanism's strain and penetration
/// budgets; the leg slides follow the body's stiffness class.
void choose_robot_stiffness(const scene::PseudoRigid& p, RobotModel& r) {
  pr::Mechanism& m = r.mechanism;
  pr::StiffnessSettings ss;
  ss.internal_auto = p.internal_auto;
  ss.contact_auto = p.contact_auto;
  ss.strain_budget = p.strain_budget;
  ss.penetration_budget = p.penetration_budget;
  r.stiffness = pr::choose_stiffness(m, ss);
  if (p.internal_auto) {
    // The leg slides are constraints of the same stiffness class as the body.
    for (int si : r.slide) {
      if (si >= 0) m.surfaces[si].stiffness = r.stiffness.internal_max;
    }
  }
  if (p.contact_auto) {
    for (int si : r.slide) {
      if (si >= 0 && !p.internal_auto) m.surfaces[si].stiffness = p.internal_stiffness;
    }
  }
}

}  // namespace

RobotModel build_robot(const scene::Scene& s) {
  // The legs are placed for the touchdown the ballistic flight reaches (its time
  // sqrt(2 dz / g)) and the energy is measured against M g h: neither exists without gravity.
  if (!(s.gravity > 0.0)) {
    std::ostringstream g;
    g << s.gravity;
    throw std::invalid_argument("gravity " + g.str() +
                                " m/s^2: the full model needs gravity > 0 (its legs are placed "
                                "for the touchdown a ballistic flight reaches; without gravity "
                                "no flight ends)");
  }
  const scene::PseudoRigid& p = s.pseudo_rigid;
  RobotModel r;
  r.spring_legs = p.legs == scene::PseudoRigid::Legs::kSpring && !s.legs.body_only;
  r.quasi_static_feet = r.spring_legs && p.feet == scene::PseudoRigid::Feet::kQuasiStatic;
  r.body_mass = s.body.mass;
  pr::Mechanism& m = r.mechanism;
  m.name = s.name;
  m.gravity = Vector3d(0.0, 0.0, -s.gravity);
  m.simulation.solver = p.solver;
  m.simulation.energy_blowup_factor = p.energy_blowup_factor;
  // Body-level error norm (optional): the solver controls the motion of the body
  // (CoM, attitude) and of the feet, not the internal vibration of the stiff springs.
  const bool rigid = p.body == scene::PseudoRigid::BodyKind::kRigid;
  // (A rigid body's states are body-level already: the setting is unused there.)
  m.simulation.error_norm =
      p.body_error_norm && !rigid ? pr::ErrorNorm::kBody : pr::ErrorNorm::kState;

  // Hips: a body-only scene pushes at the CoM through one virtual leg.
  std::vector<Vector3d> hips =
      s.legs.body_only ? std::vector<Vector3d>{Vector3d::Zero()} : s.legs.hips;
  const bool dummy = p.hips == scene::PseudoRigid::Hips::kDummy;
  if (dummy && rigid) throw std::invalid_argument("a rigid body has no dummy hip masses");
  if (r.quasi_static_feet && dummy) {
    throw std::invalid_argument(
        "quasi-static feet need hips on the body (\"hips\": \"ghost_points\"), not dummy hip "
        "masses");
  }
  Vector3d offset = Vector3d::Zero();
  const pr::BodySpec b = add_robot_body(s, hips, dummy, rigid, r, &offset);
  for (size_t i = 0; i < hips.size(); ++i) add_robot_leg(s, i, hips[i], offset, dummy, b, r);
  if (r.spring_legs && !r.quasi_static_feet) add_robot_ground(p, r);
  if (p.internal_auto || p.contact_auto) choose_robot_stiffness(p, r);
  std::string why;
  if (!m.validate(&why)) throw std::invalid_argument("robot mechanism: " + why);
  return r;
}

}  // namespace pronk::robot
