// Attitude feedback's integral action (pseudo_rigid.attitude_trim_gain): the spring-legged
// robot of study 3 running after a moving setpoint touches down with a standing roll and
// pitch bias (the stride-level PD balances a steady moment with a standing tilt, and the
// stance feedback holds the body level during the stance, where the bias does not come
// from). The integral action learns the bias away: its reference is the setpoint itself,
// level touchdowns.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "io/load/scene_loader.hpp"
#include "sim/simulate.hpp"

namespace {

struct Bias {
  double roll = 0.0, pitch = 0.0;  ///< mean touchdown roll, pitch over the last 8 strides [deg]
};

Bias touchdown_bias(double gain, double hip_shift_x = 0.0, double trim_max = 0.2) {
  const std::string scene_path = std::string(PRONK_SOURCE_DIR) + "/studies/scenes/pr_running.json";
  // pr_running undisturbed, on Verlet with the energy thrust and study 3's first tuned gains.
  pronk::scene::Scene s = pronk::io::load_scene(
      scene_path, {R"(/pseudo_rigid/solver={"method": "verlet", "h_fixed": 1.5e-4})",
                   R"(/pseudo_rigid/thrust="energy")",
                   "/initial/position=[0,0,0.4]",
                   "/initial/attitude_deg=[0,0,0]",
                   "/controller/kp/3=0.0436",
                   "/controller/kd/3=0.00627",
                   "/controller/kp/4=0.00348",
                   "/controller/kd/4=0.00787",
                   "/pseudo_rigid/leg_stiffness=926",
                   "/pseudo_rigid/leg_damping=9.55",
                   "/pseudo_rigid/stance_attitude/kp=[0.616,14.73]",
                   "/pseudo_rigid/stance_attitude/kd=[5.91,11.78]",
                   "/pseudo_rigid/hop_trim_gain=0.484",
                   "/controller/kp/0=1.449",
                   "/controller/kd/0=2.063",
                   "/controller/kp/1=1.652",
                   "/controller/kd/1=2.077",
                   "/controller/bank/kp=0.0486",
                   "/controller/bank/kd=0.0892",
                   "/pseudo_rigid/position_trim_gain=0.332",
                   "/simulation/duration=12",
                   "/pseudo_rigid/attitude_trim_gain=" + std::to_string(gain),
                   "/pseudo_rigid/attitude_trim_max=" + std::to_string(trim_max)});
  for (auto& hip : s.legs.hips) hip.x() += hip_shift_x;  // the CoM moved by -hip_shift_x
  pronk::RunOptions o;
  o.record_trajectory = false;
  const pronk::RunResult r = pronk::simulate(s, o);
  REQUIRE(r.run.status == pronk::reduced::RunStatus::kCompleted);
  const auto& st = r.run.strides;
  REQUIRE(st.size() >= 20);
  Bias b;
  for (size_t k = st.size() - 8; k < st.size(); ++k) {
    b.roll += st[k].euler123.x() * 180.0 / M_PI / 8.0;
    b.pitch += st[k].euler123.y() * 180.0 / M_PI / 8.0;
  }
  return b;
}

}  // namespace

TEST_CASE("attitude integral action: touchdowns level out where the PD alone leaves a bias",
          "[robot][attitude_trim]") {
  const Bias off = touchdown_bias(0.0);
  const Bias on = touchdown_bias(1.0);
  INFO("gain 0: roll " << off.roll << " deg, pitch " << off.pitch << " deg; gain 1: roll "
                       << on.roll << " deg, pitch " << on.pitch << " deg");
  CHECK(std::hypot(off.roll, off.pitch) > 0.4);  // the standing bias the PD leaves
  CHECK(std::abs(off.pitch) > 0.4);              // here the bias is in pitch (measured: -0.69 deg)
  CHECK(std::abs(on.pitch) < 0.1);               // learnt away (measured: -0.03 deg)
  CHECK(std::abs(on.roll) <= std::abs(off.roll) + 0.05);  // and the roll not made worse
  CHECK(std::hypot(on.roll, on.pitch) < 0.5 * std::hypot(off.roll, off.pitch));
}

// The trim's limit (pseudo_rigid.attitude_trim_max): the CoM moved 7.5 mm behind the hips'
// centre makes a steady pitch moment at every thrust. Integral action removes a steady error
// only while its integrator is inside its limit: at the default 0.2 rad the trim sits at the
// limit and the touchdowns keep a standing pitch (measured 1.07 deg); with room to 0.4 rad most
// of it is learnt away (0.38 deg). Not a rule that more is better: at 1 cm the stance
// feedback's moment limit binds first and 0.4 rad holds 4.5 deg against 3.5 deg at 0.2.
TEST_CASE("attitude integral action: its limit bounds the moment bias it can learn away",
          "[robot][attitude_trim]") {
  const Bias tight = touchdown_bias(1.0, 0.0075, 0.2);
  const Bias room = touchdown_bias(1.0, 0.0075, 0.4);
  INFO("limit 0.2: pitch " << tight.pitch << " deg; limit 0.4: pitch " << room.pitch << " deg");
  CHECK(std::abs(tight.pitch) > 0.8);
  CHECK(std::abs(room.pitch) < 0.5 * std::abs(tight.pitch));
}
