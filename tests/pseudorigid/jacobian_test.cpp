// The analytic Jacobian of every component type against central differences
// of the right-hand side.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/pseudorigid/builder.hpp"
#include "sim/pseudorigid/system.hpp"

using namespace pronk::pseudorigid;

namespace {

/// A body with a deformed, moving state so every term is exercised.
Mechanism base_body(int* body) {
  Mechanism m;
  BodySpec b;
  b.mass = 1.5;
  b.inertia = Eigen::Vector3d(0.0074, 0.0106, 0.0164).asDiagonal();
  b.com = Eigen::Vector3d(0.1, -0.2, 0.3);
  b.attitude = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  b.velocity = Eigen::Vector3d(0.3, 0.1, -0.5);
  b.omega = Eigen::Vector3d(1.0, -2.0, 0.5);
  b.internal_stiffness = 1e4;
  b.internal_damping = 3.0;
  std::string err;
  *body = add_body(m, b, &err);
  // Deform it a little.
  for (int i = 0; i < 4; ++i) m.masses[i].position += 0.003 * Eigen::Vector3d(i, -i * i, 1.0 - i);
  return m;
}

double check(const Mechanism& m, double t = 0.5) {
  MechanismSystem sys(m);
  sys.set_segment_time(t);
  int r = 0, c = 0;
  const double e = jacobian_check(sys, t, m.initial_state(), &r, &c);
  INFO("worst entry (" << r << ", " << c << ")");
  return e;
}

}  // namespace

TEST_CASE("analytic Jacobian matches central differences for every component", "[pseudorigid]") {
  int b = 0;
  SECTION("body: internal springs and dampers") {
    Mechanism m = base_body(&b);
    CHECK(check(m) < 1e-6);
  }
  SECTION("connections: spring with and without rest length, damper, friction, drag, ghost") {
    Mechanism m = base_body(&b);
    const NodeRef g = add_ghost_point(m, b, "hip", Eigen::Vector3d(0.14, 0.115, -0.04));
    const NodeRef f =
        add_mass(m, "foot", 0.05, Eigen::Vector3d(0.3, 0.0, 0.0), Eigen::Vector3d(0.2, -0.4, 1.0));
    const NodeRef a = add_anchor(m, "pivot", Eigen::Vector3d(1.0, 1.0, 1.0));
    Connection c;
    c.a = f;
    c.b = g;
    c.stiffness = 300.0;
    c.rest_length = 0.1;
    c.damping = 2.0;
    c.friction = 0.7;
    c.drag = 0.3;
    m.connections.push_back(c);
    c.a = g;
    c.b = a;
    c.rest_length = 0.0;
    c.damping = 0.0;
    m.connections.push_back(c);
    CHECK(check(m) < 1e-6);
  }
  SECTION("PD actuator, unsaturated and saturated") {
    Mechanism m = base_body(&b);
    const NodeRef f =
        add_mass(m, "foot", 0.05, Eigen::Vector3d(0.3, 0.0, 0.0), Eigen::Vector3d(0.2, -0.4, 1.0));
    Connection c;
    c.a = f;
    c.b = NodeRef{NodeRef::Kind::kMass, 0};
    c.kind = ConnectionClass::kActuator;
    c.stiffness = 100.0;
    c.rest_length = 0.2;
    c.damping = 5.0;
    c.force_limit = 1000.0;
    m.connections.push_back(c);
    CHECK(check(m) < 1e-6);
    m.connections.back().force_limit = 1.0;
    CHECK(check(m) < 1e-6);
  }
  SECTION("surfaces: grounded plane, line, point; attached plane, line, point") {
    for (SurfaceType type : {SurfaceType::kPlane, SurfaceType::kLine, SurfaceType::kPoint}) {
      for (bool attached : {false, true}) {
        Mechanism m = base_body(&b);
        const NodeRef f = add_mass(m, "foot", 0.05, Eigen::Vector3d(0.25, -0.1, -0.2),
                                   Eigen::Vector3d(0.2, -0.4, 1.0));
        Surface s;
        s.type = type;
        s.nodes = {f, NodeRef{NodeRef::Kind::kMass, 2}};
        s.stiffness = 1e4;
        s.damping = 4.0;
        s.direction = Eigen::Vector3d(0.2, 0.1, 1.0).normalized();
        if (attached) {
          s.nodes = {f};
          s.body = b;
          s.ghost = add_ghost_point(m, b, "hip", Eigen::Vector3d(0.1, 0.1, -0.05)).index;
        } else {
          s.point = Eigen::Vector3d(0.0, 0.0, 0.5);  // both nodes penetrate the plane
        }
        m.surfaces.push_back(s);
        INFO("type " << static_cast<int>(type) << " attached " << attached);
        CHECK(check(m) < 1e-6);
      }
    }
  }
  SECTION("grounded plane with regularised Coulomb friction, sliding and nearly stuck") {
    for (double slip : {1e-3, 2.0}) {  // |v_t| >> v_s (Coulomb) and |v_t| < v_s (viscous)
      Mechanism m = base_body(&b);
      const NodeRef f = add_mass(m, "foot", 0.05, Eigen::Vector3d(0.25, -0.1, -0.2),
                                 Eigen::Vector3d(0.2, -0.4, 1.0));
      Surface s;
      s.nodes = {f, NodeRef{NodeRef::Kind::kMass, 2}};
      s.stiffness = 1e4;
      s.damping = 4.0;
      s.friction = 0.8;
      s.slip_velocity = slip;
      s.direction = Eigen::Vector3d(0.2, 0.1, 1.0).normalized();
      s.point = Eigen::Vector3d(0.0, 0.0, 0.5);
      m.surfaces.push_back(s);
      INFO("slip velocity " << slip);
      CHECK(check(m) < 1e-6);
    }
  }
  SECTION("forces: world force at a ghost point, body force, impulse actuator, dummy mass") {
    Mechanism m = base_body(&b);
    const NodeRef g = add_ghost_point(m, b, "hip", Eigen::Vector3d(-0.14, 0.115, -0.04));
    m.world_forces.push_back(WorldForce{"push", g, Eigen::Vector3d(3.0, -2.0, 5.0)});
    m.body_forces.push_back(BodyForce{"leg", g, b, Eigen::Vector3d(1.0, 4.0, -7.0), 0.0, 1.0});
    const NodeRef d =
        add_dummy_mass(m, b, "dummy", Eigen::Vector3d(0.05, 0.0, 0.1), 1e-3, 1e4, 0.1);
    ImpulseActuator a;
    a.node = d;
    a.body = b;
    a.direction = Eigen::Vector3d(0, 0.6, 0.8);
    a.force = 20.0;
    a.impulse = 20.0;
    m.impulse_actuators.push_back(a);
    CHECK(check(m) < 1e-6);
  }
}
