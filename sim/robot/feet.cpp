// RobotRun's feet (free stance hips): a foot landing frees its hip in pitch (the slide
// becomes a slot); lifting off, the slide takes the leg again.

#include "sim/robot/robot_run.hpp"

namespace pronk::robot::detail {

namespace pr = pseudorigid;
using Eigen::Matrix3d;
using Eigen::Vector3d;

/// A foot lands (its hip is freed in pitch) or lifts off (its slide takes the leg along
/// the leg's current direction; the foot's velocity across the line is the hip's to catch).
/// Energy changes are booked as hip work. Feet that crossed together (a symmetric landing)
/// switch together: an event fires only once.
void RobotRun::on_foot(size_t first, double t, ode::Vec& y) {
  // (a lift-off books what its leg takes away as dissipated: quasi_static_switch)
  const double d_before = run_.dissipated;
  const double e_before = sys_.energies(y).total();
  auto any_free = [&] {
    bool any = false;
    for (size_t k = 0; k < legs_; ++k) any = any || sys_.free(k);
    return any;
  };
  const bool was_free = any_free();
  for (size_t i = 0; i < legs_; ++i) {
    if (sys_.quasi_static()) {
      quasi_static_switch(i, i == first, y);
      continue;
    }
    const double z = y[6 * model_.foot[i] + 2];
    const bool land = i == first ? !sys_.free(i) : !sys_.free(i) && z <= 0.0;
    const bool lift = i == first ? sys_.free(i) : sys_.free(i) && z >= kFootLift;
    pr::SurfaceInputs& slide = data_.inputs.surfaces[model_.slide[i]];
    if (land) {
      // The hip turns freely about its pitch axis: the foot is held in the plane of
      // the leg and the body x axis (a slot), so the leg swings fore-aft but not
      // sideways (ab/adduction held).
      const Vector3d nrm = slide.direction.cross(Vector3d::UnitX());
      if (nrm.norm() > 1e-6) {
        slide.type = pr::SurfaceType::kPlane;
        slide.bilateral = true;
        slide.direction = nrm.normalized();
      } else {
        slide.holds = false;
      }
      sys_.set_free(i, true);
    } else if (lift) {
      lift_foot(i, y);
    }
  }
  const bool now_free = any_free();
  const double vz = body_com(model_, y).v.z();
  if (now_free && !was_free) {
    run_.contact_begin = t;
    run_.contact_vz = vz;
  }
  // A stance is a contact that turned the CoM's fall into a rise: a foot's brief tap (a
  // tilted landing's first foot bouncing off) is not, and must not become the stance time
  // the next placement plans with (a 2 ms "stance" puts the feet under the hips).
  if (!now_free && was_free && run_.contact_vz < 0.0 && vz > 0.0) {
    data_.spring_stance = t - run_.contact_begin;
  }
  set_actuators();
  book_work(e_before - (run_.dissipated - d_before), y);
}

/// Quasi-static foot i at a foot event (`crossed`: its own): it lands when it reached the
/// ground in the air, lifts off when the ground no longer presses it (RobotSystem::foot_event).
void RobotRun::quasi_static_switch(size_t i, bool crossed, ode::Vec& y) {
  if (!crossed && !quasi_static_due(i, y)) return;
  if (sys_.pinned(i)) {  // lifts off: the ground no longer presses it
    // What the leg holds as it leaves (its spring, slot and ground spring) stays with the
    // massless foot, whose damper takes it in the air: dissipated, as far as the body goes.
    const double e0 = sys_.energies(y).total();
    sys_.lift_foot(i, y);
    run_.dissipated += e0 - sys_.energies(y).total();
    data_.push[i] = -sys_.foot_direction()[i];
  } else if (!sys_.free(i) || sys_.foot_event(i, y) < 0.0) {
    sys_.land_foot(i, y);  // reached the ground, which would press it
  } else {
    sys_.set_free(i, false);  // a lifted foot's hip is locked once it has risen kFootLift
  }
}

/// Quasi-static foot i is due to switch at y without a crossing of its own.
bool RobotRun::quasi_static_due(size_t i, const ode::Vec& y) const {
  if (sys_.foot_event(i, y) < 0.0) return true;
  return sys_.free(i) && !sys_.pinned(i) && sys_.foot_position(i, y).z() >= kFootLift;
}

/// Foot i lifts off: its slide (a line again) takes the leg along its current direction,
/// the foot's velocity across it removed.
void RobotRun::lift_foot(size_t i, ode::Vec& y) {
  const int foot = model_.foot[i];
  pr::SurfaceInputs& slide = data_.inputs.surfaces[model_.slide[i]];
  const pr::BodyFrame f = msys_.frames(y)[model_.body];
  const Vector3d w = msys_.body_omega(model_.body, y);
  const pr::NodeRef ghost{pr::NodeRef::Kind::kGhost,
                          model_.mechanism.surfaces[model_.slide[i]].ghost};
  const Vector3d xf = y.segment<3>(6 * foot);
  const Vector3d arm = xf - msys_.node_position(ghost, y);
  if (arm.norm() > 1e-9) {
    const double m = model_.mechanism.masses[foot].mass;
    const Vector3d d = arm.normalized();
    const Vector3d vb = f.com_velocity + w.cross(xf - f.com);
    const Vector3d vrel = y.segment<3>(6 * foot + 3) / m - vb;
    y.segment<3>(6 * foot + 3) = m * (vb + vrel.dot(d) * d);
    slide.direction = f.rotation.transpose() * d;
    data_.push[i] = -slide.direction;
  }
  slide.type = pr::SurfaceType::kLine;
  slide.bilateral = false;
  slide.holds = true;
  sys_.set_free(i, false);
}

}  // namespace pronk::robot::detail
