// Relative gains against the simulated stride map: the closed-form poles of
// sim/scene/stride_response.hpp (one PD channel over a stride with a stance; the legged
// robot's lateral loop of roll PD and banking) must be the multipliers that the stride map
// of the pulse model, linearised by finite differences of simulated strides
// (reduced::analyze_stability), has at its periodic orbit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Eigenvalues>

#include "io/load/scene_loader.hpp"
#include "sim/reduced/stride_map.hpp"
#include "sim/scene/robot_scaling.hpp"
#include "tests/support/scenes.hpp"

using namespace pronk;
using cplx = std::complex<double>;

namespace {

void sort_c(std::vector<cplx>& v) {
  std::sort(v.begin(), v.end(), [](cplx x, cplx y) {
    return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag();
  });
}

// Every multiplier of the stride map against `want`, matched after sorting.
void check_multipliers(const reduced::StabilityResult& r, std::vector<cplx> want, double tol) {
  REQUIRE(r.ok);
  std::vector<cplx> got(r.multipliers.data(), r.multipliers.data() + reduced::kStrideStateSize);
  sort_c(got);
  sort_c(want);
  REQUIRE(got.size() == want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    INFO("multiplier " << i << ": got " << got[i] << ", want " << want[i]);
    CHECK(std::abs(got[i] - want[i]) < tol);
  }
}

// The vertical channel of the seed's hop law over a stance Ts: the takeoff speed is fixed,
// a touchdown speed error moves the takeoff height by Ts/2 of it: multiplier -g Ts / (2 v).
cplx vertical_multiplier(const scene::Scene& s, double ts) {
  return -s.gravity * ts / (2.0 * std::sqrt(2.0 * s.gravity * s.controller.hop_height));
}

}  // namespace

TEST_CASE("pd channel poles and gains invert each other, and reduce to the impulse map",
          "[scene][gains]") {
  const scene::StrideTiming t{0.4, 0.1};
  for (const auto& [kp, kd] : std::vector<std::pair<double, double>>{{1.0, 1.5}, {3.0, 0.4}}) {
    const auto z = scene::pd_channel_poles(kp, kd, t);
    double kp2 = 0, kd2 = 0;
    scene::pd_channel_gains(z[0], z[1], t, &kp2, &kd2);
    CHECK(kp2 == Approx(kp).epsilon(1e-12));
    CHECK(kd2 == Approx(kd).epsilon(1e-12));
  }
  // Without a stance: z1 z2 = 1 - kd, z1 + z2 = 2 - T kp - kd (the impulse map).
  const scene::StrideTiming impulse{0.4, 0.0};
  const auto z = scene::pd_channel_poles(1.0, 1.5, impulse);
  CHECK(std::abs(z[0] * z[1] - cplx(1.0 - 1.5)) < 1e-14);
  CHECK(std::abs(z[0] + z[1] - cplx(2.0 - 0.4 - 1.5)) < 1e-14);
  // A response of frequency w and damping zeta: poles exp(-zeta w T) (cos, sin)(w T sqrt(1-z^2)).
  const auto p = scene::response_poles(5.0, 0.3, 0.4);
  CHECK(std::abs(p[0]) == Approx(std::exp(-0.3 * 5.0 * 0.4)).epsilon(1e-14));
  CHECK(std::abs(std::arg(p[0])) == Approx(5.0 * 0.4 * std::sqrt(1 - 0.09)).epsilon(1e-14));
}

TEST_CASE("a stride response written per channel is the pulse model's stride map",
          "[scene][gains][stability]") {
  // The body-only robot of case 1 in the pulse model, 80 ms stances: each channel's gains come
  // from a natural frequency and a damping ratio, turned into impulses with the mass, the
  // inertia and the stride period (0.404 s of flight + the stance).
  const scene::Scene s = test::load_shipped(
      "case1_body_only", {"/model=\"pulse\"", R"(/pulse={"mode": "duration", "duration": 0.08})",
                          R"(/controller/gains={"natural_frequency": [4, 5, 6, 3, 2],
                             "damping_ratio": [0.5, 0.7, 0.3, 1.2, 0.9]})"});
  const scene::StrideTiming t = scene::design_stride(s);
  CHECK(t.stance == 0.08);
  CHECK(t.flight == Approx(2 * std::sqrt(2 * 9.81 * 0.2) / 9.81).epsilon(1e-15));
  // The absolute gains are the relative ones times the mass and the inertia.
  const double w[] = {4, 5, 6, 3, 2}, zeta[] = {0.5, 0.7, 0.3, 1.2, 0.9};
  std::vector<cplx> want;
  for (int c = 0; c < 5; ++c) {
    for (cplx z : scene::response_poles(w[c], zeta[c], t.period())) want.push_back(z);
  }
  want.push_back(vertical_multiplier(s, t.stance));
  check_multipliers(reduced::analyze_stability(s), want, 1e-6);
}

TEST_CASE("relative gains per unit mass and inertia are the pulse model's stride map",
          "[scene][gains][stability]") {
  // The seed's gains written relative (kp 1/s, kd 1.5 per unit mass and inertia) on a body
  // 4x heavier with another inertia: the multipliers depend on the relative gains only.
  const scene::Scene s = test::load_shipped(
      "case1_body_only",
      {"/model=\"pulse\"", R"(/pulse={"mode": "duration", "duration": 0.12})",
       R"(/body={"mass": 6, "inertia": [0.05, 0.08, 0.11]})",
       R"(/controller/gains={"kp": [2, 0.5, 0, 3, 1, 0.2], "kd": [0.5, 1, 1, 1.2, 0.8, 1.9]})"});
  CHECK(s.controller.kp[0] == 2 * 6.0);
  CHECK(s.controller.kd[4] == 0.8 * 0.08);
  CHECK(s.controller.kd[2] == 6.0);  // the hop-height law: Kd_z = m
  const scene::StrideTiming t = scene::design_stride(s);
  const double kp[] = {2, 0.5, 3, 1, 0.2}, kd[] = {0.5, 1, 1.2, 0.8, 1.9};
  std::vector<cplx> want;
  for (int c = 0; c < 5; ++c) {
    for (cplx z : scene::pd_channel_poles(kp[c], kd[c], t)) want.push_back(z);
  }
  want.push_back(vertical_multiplier(s, t.stance));
  check_multipliers(reduced::analyze_stability(s), want, 1e-6);
}

TEST_CASE("the legged robot's default lateral loop has the placed poles in the pulse model",
          "[scene][gains][stability]") {
  // The three-legged robot of issue 35, left to its defaults (banking on, roll and bank gains
  // placed at kLateralPoles on its stride), hopping 0.3 m with 60 ms stances. The stride map's
  // multipliers: the four placed poles, the x, pitch and yaw pairs of the seed gains, and the
  // vertical one.
  nlohmann::json doc = nlohmann::json::parse(R"({
    "model": "pulse",
    "body": {"mass": 1.5, "inertia": [0.006, 0.009, 0.012]},
    "legs": {"kind": "legged", "hips": [[0.15, 0, -0.04], [-0.08, 0.13, -0.04], [-0.08, -0.13, -0.04]]},
    "controller": {"hop_height": 0.3, "setpoint": {"velocity": [0.4, 0, 0]}},
    "pulse": {"mode": "duration", "duration": 0.06}
  })");
  const scene::Scene s = io::parse_scene(doc, "three_legs.json");
  REQUIRE(s.controller.bank_enabled);
  const scene::StrideTiming t = scene::design_stride(s);
  std::vector<cplx> want(scene::kLateralPoles.begin(), scene::kLateralPoles.end());
  for (int channel = 0; channel < 3; ++channel) {  // x, pitch, yaw: the seed's kp 1/s, kd 1.5
    for (cplx z : scene::pd_channel_poles(1.0, 1.5, t)) want.push_back(z);
  }
  want.push_back(vertical_multiplier(s, t.stance));
  // The x, pitch and yaw channels share one pair: a triple root, which the finite-difference
  // Jacobian splits by ~2e-5. The placed lateral poles are simple: each within 1e-5.
  const reduced::StabilityResult r = reduced::analyze_stability(s);
  check_multipliers(r, want, 1e-4);
  for (double pole : scene::kLateralPoles) {
    double nearest = 1.0;
    for (int i = 0; i < reduced::kStrideStateSize; ++i)
      nearest = std::min(nearest, std::abs(r.multipliers[i] - cplx(pole)));
    INFO("placed pole " << pole);
    CHECK(nearest < 1e-5);
  }
  // In max-force mode the stance is the time 3 legs of 60 N take: Ts = 2 m v / (3 F - m g).
  doc["pulse"] = {{"mode", "max_force"}};
  const scene::Scene f = io::parse_scene(doc, "three_legs.json");
  const double v = std::sqrt(2 * 9.81 * 0.3);
  CHECK(scene::design_stride(f).stance == Approx(2 * 1.5 * v / (180 - 1.5 * 9.81)).epsilon(1e-14));
}

TEST_CASE("position loop with integral action: placed poles, and the map against a stride",
          "[scene][gains]") {
  for (const scene::StrideTiming t : {scene::StrideTiming{0.49, 0.10}, {0.40, 0.14}, {0.30, 0.0}}) {
    for (const std::array<double, 3>& p :
         {std::array<double, 3>{0.6, 0.6, 0.6}, {0.3, 0.5, 0.8}, {0.45, 0.55, 0.7}}) {
      const scene::PositionLoop l = scene::place_position_poles(p, t);
      CHECK(l.kp > 0.0);
      CHECK(l.trim > 0.0);
      // The map's eigenvalues, computed numerically, are the poles asked for.
      const Eigen::EigenSolver<Eigen::Matrix3d> es(scene::position_stride_map(l, t));
      std::vector<double> got;
      for (int i = 0; i < 3; ++i) {
        // A triple pole splits by ~eps^(1/3) in floating point.
        CHECK(std::abs(es.eigenvalues()[i].imag()) < 1e-4);
        got.push_back(es.eigenvalues()[i].real());
      }
      std::sort(got.begin(), got.end());
      std::array<double, 3> want = p;
      std::sort(want.begin(), want.end());
      for (int i = 0; i < 3; ++i) CHECK(std::abs(got[i] - want[i]) < 1e-4);
    }
  }
  // The map against one stride of a point mass that tracks a moving setpoint: at touchdown
  // the trim grows by g e, a constant force over the stance delivers the PD impulse on the
  // perceived error, then it flies. Exact kinematics, no linearisation.
  const scene::StrideTiming t{0.45, 0.12};
  const scene::PositionLoop l = scene::place_position_poles({0.5, 0.6, 0.7}, t);
  const double m = 2.3, v_d = 0.4, t0 = 1.7;
  const double x = 0.05 + v_d * t0, v = 0.31, trim = -0.02;  // at touchdown t0
  const double e = x - v_d * t0;
  const double trim1 = trim + l.trim * e;
  const double P = m * (l.kp * (v_d * t0 - (x + trim1)) + l.kd * (v_d - v));
  const double F = P / t.stance;
  const double x_to = x + v * t.stance + 0.5 * F / m * t.stance * t.stance;
  const double v1 = v + F / m * t.stance;
  const double x1 = x_to + v1 * t.flight;
  const double t1 = t0 + t.period();
  const Eigen::Vector3d next = scene::position_stride_map(l, t) * Eigen::Vector3d(e, v - v_d, trim);
  CHECK(next(0) == Approx(x1 - v_d * t1).margin(1e-12));
  CHECK(next(1) == Approx(v1 - v_d).margin(1e-12));
  CHECK(next(2) == Approx(trim1).margin(1e-12));
}
