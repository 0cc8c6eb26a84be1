#include "sim/robot/sampled_contacts.hpp"

#include <algorithm>
#include <cmath>

namespace pronk::robot {

namespace {

bool on_ground(const RobotSample& s) {
  return std::any_of(s.normal_force.begin(), s.normal_force.end(),
                     [](double n) { return n > 0.0; });
}

/// The lowest foot's height at a sample [m] (+inf without feet).
double lowest_foot(const RobotSample& s) {
  double z = INFINITY;
  for (double f : s.foot_z) z = std::min(z, f);
  return z;
}

/// One contact as the samples go: its start, its last lift, whether the feet rose past the
/// lift height since, and whether the CoM turned from falling to rising within it.
struct Contact {
  double begin = -1.0, end = -1.0;
  bool risen = false, turned = false;
  bool open() const { return begin >= 0.0; }
};

}  // namespace

std::vector<double> sampled_contact_times(const RobotRunResult& r, double lift) {
  std::vector<double> out;
  const auto& s = r.samples;
  const auto& traj = r.run.trajectory;
  if (s.size() != traj.size()) return out;
  Contact c;
  for (size_t k = 1; k < s.size(); ++k) {
    const bool was = on_ground(s[k - 1]), is = on_ground(s[k]);
    const double mid = 0.5 * (s[k - 1].t + s[k].t);
    if (!was && is) {
      // A touch: the same contact after a foot's ringing, else a new one (the last, a tap
      // or a finished stance already counted, is dropped).
      if (!c.open() || c.risen) c = Contact{mid};
      c.end = -1.0;
    }
    if (was && !is && c.open()) c.end = mid;
    if (c.open() && !is && lowest_foot(s[k]) > lift) {
      if (c.turned && c.end > c.begin) out.push_back(c.end - c.begin);
      c.risen = true;
      c.turned = false;  // (counted)
    }
    const double v0 = traj[k - 1].velocity.z(), v1 = traj[k].velocity.z();
    if (c.open() && !c.risen && v0 <= 0.0 && v1 > 0.0) c.turned = true;
  }
  return out;
}

}  // namespace pronk::robot
