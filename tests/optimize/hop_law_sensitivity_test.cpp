// The sensitivity of study 2's design (pulse model) to the robot's mass, against the hop law's
// closed form. The controller believes the design's mass m̂; the plant's mass is m = m̂ (1 + ε).
// A stance pushes with the constant force F = m̂ (v1 − v0 + g T) / T for the pulse duration T
// (the hop law's impulse plus the gravity compensation, both at the believed mass), so the
// take-off speed is v_to = v0 + r (v1 − v0 + g T) − g T with r = m̂ / m, where v1(v0) is the
// pulse-aware hop law's take-off speed for the apex h above touchdown:
//     v1 = −g T / 2 + sqrt((g T / 2)² + 2 g h − g v0 T).
// The apex above touchdown is A = (v0 + v_to) T / 2 + v_to² / (2 g) and the next touchdown speed
// v0' = −sqrt(2 g A). Its fixed point gives the steady apex error e*(ε) = A − h; r = 1 gives
// e* = 0 (the law is exact for the mass it believes). Because the compensation m̂ g T falls
// short by ε m̂ g T over a long stance and the law answers a low apex with a harder push from a
// slower touchdown, e* is large: de*/dε ≈ −3.1 m for study 2 (T = 0.389 s, h = 0.2 m).
//
// hop_height_error is an RMS over strides: unsigned, with its minimum at the design, so its
// two-sided derivative there says nothing (a central difference sees the V's asymmetry only).
// What the hop law predicts is its one-sided change: at mass m̂ (1 ± δ) the RMS is ≈ |e*(±δ)|
// (the transient converges in a few strides). The test checks both one-sided values, and so
// the one-sided elasticities, against the closed form.
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "io/load/scene_loader.hpp"
#include "optimize/sensitivity/design_sensitivity.hpp"

namespace {

namespace sens = pronk::optimize::sensitivity;

// The steady apex error e*(eps) of the stride map above (vertical, level body).
double steady_apex_error(double eps, double g, double h, double T) {
  const double r = 1.0 / (1.0 + eps);
  const double half = 0.5 * g * T;
  double v0 = -std::sqrt(2.0 * g * h), apex = h;
  for (int i = 0; i < 10000; ++i) {
    const double v1 = -half + std::sqrt(std::max(half * half + 2.0 * g * h - g * v0 * T, half * half));
    const double vto = v0 + r * (v1 - v0 + g * T) - g * T;
    apex = 0.5 * (v0 + vto) * T + vto * vto / (2.0 * g);
    const double next = -std::sqrt(2.0 * g * std::max(apex, 0.0));
    if (std::abs(next - v0) < 1e-15) break;
    v0 = next;
  }
  return apex - h;
}

}  // namespace

TEST_CASE("study 2: hop_height_error with the mass 1 % off matches the hop law's closed form",
          "[sensitivity]") {
  const std::string path =
      std::string(PRONK_SOURCE_DIR) + "/results/study2_legged_pulse_duty50/design.json";
  const nlohmann::json design = pronk::io::read_json_file(path);
  sens::DesignSensitivityOptions opt;
  opt.only = {"/body/mass"};
  opt.default_range = 0.01;
  opt.sobol.samples = 0;
  opt.threads = 2;
  const sens::DesignSensitivity s = sens::design_sensitivity(design, path, opt);
  REQUIRE(s.inputs.size() == 1);
  size_t k = 0;
  while (k < s.outputs.size() && s.outputs[k] != "hop_height_error") ++k;
  REQUIRE(k < s.outputs.size());

  const nlohmann::json& scene = design.at("scene");
  const double g = scene.at("gravity").get<double>();
  const double h = scene.at("controller").at("hop_height").get<double>();
  const double T = design.at("parameters").at("pulse_duration").get<double>();
  const double lighter = std::abs(steady_apex_error(-0.01, g, h, T));
  const double heavier = std::abs(steady_apex_error(0.01, g, h, T));
  // The slope the law predicts, and the size that makes it matter: 1 % of mass moves the apex
  // by about 15 % of the hop height.
  const double slope = (steady_apex_error(1e-5, g, h, T) - steady_apex_error(-1e-5, g, h, T)) / 2e-5;
  CHECK(slope == Approx(-3.08).margin(0.05));
  const double f0 = s.local.f0[k];
  INFO("hop_height_error: design " << f0 << ", mass -1 % " << s.low[k][0] << " (law " << lighter
                                   << "), mass +1 % " << s.high[k][0] << " (law " << heavier << ")");
  CHECK(f0 < 0.1 * heavier);  // the design holds its apex
  CHECK(s.low[k][0] == Approx(lighter).epsilon(0.03));
  CHECK(s.high[k][0] == Approx(heavier).epsilon(0.03));
  // One-sided elasticities: % change of the error per % of mass, each side.
  const double up = (s.high[k][0] - f0) / f0 / 0.01, down = (s.low[k][0] - f0) / f0 / -0.01;
  const double up_law = (heavier - f0) / f0 / 0.01, down_law = (lighter - f0) / f0 / -0.01;
  CHECK(up > 0.0);
  CHECK(down < 0.0);
  CHECK(up == Approx(up_law).epsilon(0.03));
  CHECK(down == Approx(down_law).epsilon(0.03));
}
