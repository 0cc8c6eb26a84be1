// The fidelity ladder's full-model rungs run the full model: the pseudo-rigid rung (four
// masses on 1e6 N/m springs) and the rigid rung, against the pulse rung on the same robot.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "app/bench/suite.hpp"
#include "io/load/scene_loader.hpp"

TEST_CASE("fidelity ladder: the full-model rungs run the full model, not the pulse model",
          "[cli][bench][heavy]") {
  pronk::app::bench::BenchConfig c;
  c.quick = false;
  c.repeat = 1;
  c.studies_dir = std::string(PRONK_SOURCE_DIR) + "/studies";
  pronk::scene::Scene s = pronk::io::load_scene(c.studies_dir + "/scenes/case3_legged_pulse.json");
  s.simulation.duration = 2.0;
  pronk::app::bench::FidelityPoint pulse, rigid, four;
  for (const auto& rung : pronk::app::bench::fidelity_rungs()) {
    if (rung.model == "pulse") pulse = rung.run(s, c);
    if (rung.model == "rigid") rigid = rung.run(s, c);
    if (rung.model == "pseudo_rigid") four = rung.run(s, c);
  }
  INFO("pulse " << pulse.cost_per_sim_s << " s/s; rigid " << rigid.cost_per_sim_s << " s/s ("
                << rigid.note << "); four-mass " << four.cost_per_sim_s << " s/s (" << four.note
                << ")");
  REQUIRE(four.status == "completed");
  REQUIRE(rigid.status == "completed");
  // Only the full model reports its internal stiffness (the pulse model has none).
  CHECK(four.note.find("internal k 1000000") != std::string::npos);
  // What ran: simulate() reports the model it ran, and the solver's counters (deterministic,
  // unlike CPU times, which belong in the bench) tell the full model's state from the pulse
  // model's. Measured: 250 right-hand sides on the pulse rung, 1246 on the rigid rung (the
  // pulse model's motion, integrated by auto's DOPRI5 at the full model's tolerance), 39 922
  // on the four-mass rung (its 1e6 N/m springs bound the explicit step).
  INFO("rhs: pulse " << pulse.rhs_evaluations << ", rigid " << rigid.rhs_evaluations
                     << ", four-mass " << four.rhs_evaluations);
  CHECK(pulse.ran_model == "pulse");
  CHECK(four.ran_model == "pseudo_rigid");
  CHECK(rigid.ran_model == "pseudo_rigid");
  CHECK(four.rhs_evaluations > 30 * pulse.rhs_evaluations);
  CHECK(rigid.rhs_evaluations > 2 * pulse.rhs_evaluations);
  // Same robot, same gait: the apexes agree to a few millimetres.
  CHECK(std::abs(four.mean_apex - pulse.mean_apex) < 0.01);
  CHECK(std::abs(rigid.mean_apex - pulse.mean_apex) < 0.01);
}
