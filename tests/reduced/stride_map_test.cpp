// Gait stability from the stride map against multipliers derived by hand.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "sim/reduced/stride_map.hpp"
#include "tests/support/scenes.hpp"

using namespace pronk;

namespace {

// Multipliers of one PD channel of the body-only impulse model (see
// simulator_test.cpp): A = [[1 - a T, (1 - b) T], [-a, 1 - b]] with a = Kp/m
// (or Kp/I), b = Kd/m (or Kd/I), T = 2 sqrt(2 g h) / g.
std::vector<std::complex<double>> pd_pair(double a, double b, double T) {
  const double tr = (1 - a * T) + (1 - b), det = (1 - a * T) * (1 - b) + a * (1 - b) * T;
  const std::complex<double> disc = std::sqrt(std::complex<double>(tr * tr - 4 * det));
  return {0.5 * (tr + disc), 0.5 * (tr - disc)};
}

// Sorts complex numbers by (real, imag) for comparison.
void sort_c(std::vector<std::complex<double>>& v) {
  std::sort(v.begin(), v.end(), [](auto x, auto y) {
    return x.real() != y.real() ? x.real() < y.real() : x.imag() < y.imag();
  });
}

void check_multipliers(const reduced::StabilityResult& r, std::vector<std::complex<double>> want) {
  REQUIRE(r.ok);
  std::vector<std::complex<double>> got(r.multipliers.data(), r.multipliers.data() + 11);
  sort_c(got);
  sort_c(want);
  REQUIRE(got.size() == want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    INFO("multiplier " << i << ": got " << got[i] << ", want " << want[i]);
    CHECK(std::abs(got[i] - want[i]) < 1e-6);
  }
}

}  // namespace

TEST_CASE("stride map multipliers of the body-only model match the hand derivation",
          "[stability]") {
  auto scene = test::load_shipped("case1_body_only");
  const double g = scene.gravity, h = scene.controller.hop_height;
  const double T = 2 * std::sqrt(2 * g * h) / g;
  SECTION("seed gains: every PD channel has a = 1, b = 1.5; the hop-height law is dead-beat") {
    const auto r = reduced::analyze_stability(scene);
    std::vector<std::complex<double>> want;
    for (int channel = 0; channel < 5; ++channel) {  // x, y, roll, pitch, yaw
      for (auto m : pd_pair(1.0, 1.5, T)) want.push_back(m);
    }
    want.push_back(0.0);  // vertical: v_z at the next touchdown is -sqrt(2 g h) whatever it was
    check_multipliers(r, want);
    CHECK(r.spectral_radius == Approx(0.7568115).epsilon(1e-6));
    CHECK(r.period == Approx(T).epsilon(1e-9));
    // The orbit: on the setpoint, level, falling at sqrt(2 g h).
    CHECK(r.fixed_point.norm() == Approx(std::sqrt(2 * g * h)).epsilon(1e-9));
  }
  SECTION("other gains per channel give their own pairs, complex ones included") {
    const double m = scene.body.mass;
    const Eigen::Vector3d I = scene.body.inertia.diagonal();
    scene.controller.kp << 2.0 * m, 0.5 * m, 0.0, 3.0 * I.x(), 1.0 * I.y(), 0.2 * I.z();
    scene.controller.kd << 0.5 * m, 1.0 * m, m, 1.2 * I.x(), 0.8 * I.y(), 1.9 * I.z();
    const auto r = reduced::analyze_stability(scene);
    std::vector<std::complex<double>> want;
    const double a[] = {2.0, 0.5, 3.0, 1.0, 0.2}, b[] = {0.5, 1.0, 1.2, 0.8, 1.9};
    for (int c = 0; c < 5; ++c) {
      for (auto mu : pd_pair(a[c], b[c], T)) want.push_back(mu);
    }
    want.push_back(0.0);
    check_multipliers(r, want);
  }
}

TEST_CASE("an unstable gait has spectral radius above one, a falling one gets the penalty",
          "[stability]") {
  auto scene = test::load_shipped("case1_body_only");
  const double m = scene.body.mass;
  scene.controller.kp[1] = 6.0 * m;  // a = 6: the lateral loop overshoots (|multiplier| > 1)
  const auto r = reduced::analyze_stability(scene);
  const double g = scene.gravity, h = scene.controller.hop_height;
  const double T = 2 * std::sqrt(2 * g * h) / g;
  double want = 0.0;
  for (auto mu : pd_pair(6.0, 1.5, T)) want = std::max(want, std::abs(mu));
  REQUIRE(want > 1.0);
  // Newton finds the (unstable) orbit; its multiplier is the hand-derived one.
  REQUIRE(r.ok);
  CHECK(r.spectral_radius == Approx(want).epsilon(1e-6));

  auto falling = test::load_shipped("case2_legged_impulse");
  falling.controller.kp[3] = 0.0;  // no roll control and a tiny hop: it cannot hold an orbit
  falling.controller.kd[3] = 0.0;
  falling.controller.kp[4] = -1.0;
  const auto f = reduced::analyze_stability(falling, {}, 42.0);
  if (!f.ok) {
    CHECK(f.spectral_radius == 42.0);
    CHECK_FALSE(f.reason.empty());
  } else {
    CHECK(f.spectral_radius > 1.0);
  }
}
