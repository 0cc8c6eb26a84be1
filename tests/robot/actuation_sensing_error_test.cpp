// Actuation and sensing errors of the full model's robot (pseudo_rigid.actuator_gain,
// pseudo_rigid.attitude_sensor_bias_deg): the plant's, unknown to the controller.
// References: the energy balance (the actuators' work is booked from the forces they
// deliver, so it must close whatever the gain), and the attitude the controller levels
// (a sensor that reads the pitch b high makes the controller hold the body at -b).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "sim/simulate.hpp"
#include "tests/support/scenes.hpp"

namespace {

pronk::RunResult run(const std::vector<std::string>& overrides) {
  std::vector<std::string> o = {"/controller/setpoint/velocity=[0,0,0]",
                                "/initial/velocity=[0,0,0]", "/initial/position=[0,0,0.55]",
                                "/initial/attitude_quaternion=[1,0,0,0]"};
  o.insert(o.end(), overrides.begin(), overrides.end());
  const pronk::scene::Scene s = pronk::test::load_test_scene("tripod_first_design", o);
  pronk::RunOptions opt;
  opt.record_trajectory = false;
  pronk::RunResult r = pronk::simulate(s, opt);
  REQUIRE(r.run.status == pronk::reduced::RunStatus::kCompleted);
  REQUIRE(r.run.strides.size() >= 12);
  return r;
}

double first_apex(const pronk::RunResult& r) {
  for (const auto& s : r.run.strides)
    if (s.has_apex) return s.apex_height;
  return 0.0;
}

// Mean touchdown pitch over the last 6 strides [deg].
double late_pitch_deg(const pronk::RunResult& r) {
  const auto& st = r.run.strides;
  double p = 0.0;
  for (size_t k = st.size() - 6; k < st.size(); ++k) p += st[k].euler123.y() * 180.0 / M_PI / 6.0;
  return p;
}

}  // namespace

TEST_CASE("actuation error: a stronger or weaker actuator, the energy balance still closes",
          "[robot][actuation_error]") {
  const pronk::RunResult exact = run({});
  const pronk::RunResult strong = run({"/pseudo_rigid/actuator_gain=1.3"});
  const pronk::RunResult weak = run({"/pseudo_rigid/actuator_gain=0.7"});
  INFO("first apex: exact " << first_apex(exact) << ", x1.3 " << first_apex(strong) << ", x0.7 "
                            << first_apex(weak) << " m; energy drift "
                            << exact.monitors.energy_drift << ", " << strong.monitors.energy_drift
                            << ", " << weak.monitors.energy_drift << " J");
  // The thrust the controller planned for the target apex, delivered 30 % off.
  CHECK(first_apex(strong) > first_apex(exact) + 0.01);
  CHECK(first_apex(weak) < first_apex(exact) - 0.01);
  // Work booked from the forces delivered: the balance closes as well as the exact run's.
  const double scale = exact.monitors.energy_scale;
  CHECK(strong.monitors.energy_drift < 1e-3 * scale);
  CHECK(weak.monitors.energy_drift < 1e-3 * scale);
}

TEST_CASE("sensing error: the controller levels what it reads, the body settles at minus the bias",
          "[robot][sensing_error]") {
  const double level = late_pitch_deg(run({}));
  const double biased = late_pitch_deg(run({"/pseudo_rigid/attitude_sensor_bias_deg=[0,2]"}));
  INFO("late touchdown pitch: exact " << level << " deg, sensor +2 deg: " << biased << " deg");
  CHECK(std::abs(level) < 0.2);
  CHECK(biased - level == Approx(-2.0).margin(0.3));
}
