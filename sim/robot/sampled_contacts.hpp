// Stance times read off a robot run's samples, for any feet and any hips: first foot down to
// last foot up, as RobotRun counts a stance at the feet's events where it has them.
#pragma once

#include <vector>

#include "sim/robot/robot_simulator.hpp"

namespace pronk::robot {

/// Each stance's contact time [s], in order. A foot is down while the ground presses it (normal
/// force > 0). A contact lasts while some foot is down, and across gaps in which every foot
/// stays within `lift` [m] of the ground (a foot ringing on its contact). A contact is a
/// stance when the CoM's fall turns into a rise within it (a brief tap is not). Each end sits
/// halfway between the samples on either side of it: good to half the sample interval. A
/// stance still open at the end of the run, and runs without feet, give none.
std::vector<double> sampled_contact_times(const RobotRunResult& r, double lift = 2e-4);

}  // namespace pronk::robot
