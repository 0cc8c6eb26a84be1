#include "sim/pseudorigid/method_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace pronk::pseudorigid {

namespace {

constexpr double kVerletSafety = 0.8;  ///< fraction of Verlet's stability limit 2 / omega
/// The same with restarts at events, each of which adds an offset of O((omega h)^2).
constexpr double kVerletSafetyRestarts = 0.7;
constexpr double kVerletMinStep = 2e-5;     ///< below it, radau5 (rule 4) [s]
constexpr double kTightAccuracy = 1e-6;     ///< below it, an implicit high-order method (rule 2)
constexpr double kVerletBudgetShare = 0.5;  ///< of the accuracy, given to verlet's energy_tol
constexpr double kBudgetLength = 2.0;       ///< runs longer than this get less budget [s]
constexpr double kContactResolution = 0.7;
/// omega h of a ringing mode the step resolves (AutoRequest::resolve_omega): at 0.7 the first
/// stance of pr_running's four-mass body on quasi-static feet still ended with a 3 ms tap of a
/// lifted foot that a refined run does not have (contact time 5.6 % off), at 0.6 the first 10
/// strides agree within 1.1 % (rigid body 1.3 %); at 0.7 of the stability bound, 6 %.
constexpr double kRingResolution = 0.6;
/// An elastic contact this close to the stiffest mode makes the problem non-stiff (rule 5).
constexpr double kContactDominates = 0.9;  ///< omega_c h of an elastic contact

/// Rule 8 (robots without contact): tolerance relative to the accuracy, DOPRI5's stability
/// limit omega h on the real axis, and the step a pulse-driven robot's accuracy allows [s].
constexpr double kSmoothRobotTolerance = 1e-3;
constexpr double kDopri5Stability = 3.3;
/// (Case 5 at 1e8 N/m, 3.3 / omega = 1.4e-4 s: dopri5 0.33 s, radau5 0.41 s; at 1e9,
/// 4.6e-5 s: dopri5 0.83 s, radau5 0.44 s.)
constexpr double kRobotAccuracyStep = 8e-5;

/// "1.2e4 rad/s (1.9 kHz)".
std::string frequency_text(double omega) {
  char buf[80];
  const double hz = omega / (2.0 * M_PI);
  if (hz >= 1e3) {
    std::snprintf(buf, sizeof buf, "%.2g rad/s = %.2g kHz", omega, hz / 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%.2g rad/s = %.2g Hz", omega, hz);
  }
  return buf;
}

/// The scene part of the reason: "stiffest mode ..., min mass ..., contact, dissipation".
std::string scene_text(const SceneProbe& p) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "stiffest mode %s, smallest mass %.2g kg",
                frequency_text(p.omega_max).c_str(), p.min_mass);
  std::string s = buf;
  s += p.contact ? ", non-smooth contact" : ", no contact";
  s += p.dissipation ? ", dissipation" : ", no dissipation";
  return s;
}

MethodChoice adaptive(const SceneProbe& p, const AutoRequest& r, ode::Method m, double tol,
                      int rule, const char* why) {
  MethodChoice c;
  c.method = m;
  c.rtol = tol;
  c.atol = tol;
  c.accuracy = r.accuracy;
  c.probe = p;
  c.rule = rule;
  char buf[400];
  std::snprintf(buf, sizeof buf, "auto: %s rtol=atol=%.2g (%s; %s; energy budget %.2g)",
                std::string(ode::to_string(m)).c_str(), tol, why, scene_text(p).c_str(),
                r.accuracy);
  c.reason = buf;
  return c;
}

MethodChoice verlet(const SceneProbe& p, const AutoRequest& r, double h, const char* why) {
  MethodChoice c;
  c.method = ode::Method::kVerlet;
  c.h_fixed = h;
  if (r.flight_step > 0.0) c.h_flight = std::max(r.flight_step, h);
  c.energy_tol =
      r.restarts ? 0.0 : kVerletBudgetShare * r.accuracy * std::min(1.0, kBudgetLength / r.t_end);
  c.accuracy = r.accuracy;
  c.probe = p;
  c.rule = 6;
  char flight[48] = "";
  if (c.h_flight > 0.0) std::snprintf(flight, sizeof flight, " (%.2g s in flight)", c.h_flight);
  char buf[520];
  std::snprintf(buf, sizeof buf,
                "auto: verlet h=%.2g s%s, energy_tol %.2g (%s; %s; energy budget %.2g)", h, flight,
                c.energy_tol, why, scene_text(p).c_str(), r.accuracy);
  c.reason = buf;
  return c;
}

/// Verlet's step: 0.8 (0.7 with restarts) x its stability limit, or an elastic contact's ringing
/// resolved.
double verlet_step(const SceneProbe& p, const AutoRequest& r, std::string* why) {
  const double safety = r.restarts ? kVerletSafetyRestarts : kVerletSafety;
  const double stable = safety * 2.0 / p.omega_max;
  const double contact =
      p.omega_elastic_contact > 0.0 ? kContactResolution / p.omega_elastic_contact : stable;
  const double ring = r.resolve_omega > 0.0 ? kRingResolution / r.resolve_omega : stable;
  char buf[200];
  if (ring < std::min(stable, contact)) {
    std::snprintf(buf, sizeof buf,
                  "a %.2g rad/s ringing resolved: 0.6/omega = %.2g s, below the stability limit "
                  "2/omega_max = %.2g s",
                  r.resolve_omega, ring, 2.0 / p.omega_max);
  } else if (contact < stable) {
    std::snprintf(buf, sizeof buf, "elastic contact resolved: 0.7/omega_c = %.2g s", contact);
  } else {
    std::snprintf(buf, sizeof buf, "%.1f x its stability limit 2/omega = %.2g s", safety,
                  2.0 / p.omega_max);
  }
  *why = buf;
  double h = round_down_2(std::min({stable, contact, ring}));
  if (h > r.h_max) {
    h = r.h_max;
    *why += ", capped at h_max";
  }
  return h;
}

/// Rule 8: a robot without contact (force legs). Its hip forces switch at every pulse, so the
/// steps are limited by accuracy, not stability (case 5: a mean step of 2e-4 s against
/// DOPRI5's stability limit of 3.3e-3 s; 7.7e-5 s against 1.4e-4 s at 1e8 N/m); the restarts need
/// the tolerance a / 1000 for the sampled balance to stay within a. DOPRI5 while its stability
/// limit 3.3 / omega_max is above that step, RADAU5 otherwise.
MethodChoice smooth_robot(const SceneProbe& p, const AutoRequest& r) {
  const double tol = r.accuracy * kSmoothRobotTolerance;
  if (kDopri5Stability / p.omega_max >= kRobotAccuracyStep) {
    return adaptive(p, r, ode::Method::kDopri5, tol, 8,
                    "robot without contact: pulses switch the forces, the steps are limited by "
                    "accuracy, not by the stiff modes: non-stiff");
  }
  return adaptive(p, r, ode::Method::kRadau5, tol, 8,
                  "robot without contact, stiff modes above the accuracy-limited step");
}

}  // namespace

double round_down_2(double x) {
  const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
  return std::floor(x / scale * (1.0 + 1e-12)) * scale;
}

MethodChoice choose_method(const SceneProbe& p, const AutoRequest& r) {
  const double a = r.accuracy;
  if (!(p.omega_max > 0.0)) {
    return adaptive(p, r, ode::Method::kDopri5, a / 10.0, 1, "no springs: non-stiff");
  }
  if (a < kTightAccuracy) {
    return p.contact
               ? adaptive(p, r, ode::Method::kRodas4, a / 10.0, 2,
                          "budget below 1e-6: high order, contact")
               : adaptive(p, r, ode::Method::kRadau5, a / 10.0, 2, "budget below 1e-6: high order");
  }
  if (p.dissipation && !p.dissipation_split) {
    return adaptive(p, r, ode::Method::kRodas4, a / 10.0, 3,
                    "dampers on min_norm ghost points: no implicit dissipation for verlet");
  }
  if (p.omega_elastic_contact >= kContactDominates * p.omega_max) {
    return adaptive(p, r, ode::Method::kDopri5, a * 1e-4, 5,
                    "the stiffest mode is an elastic contact that must be resolved: non-stiff");
  }
  if (!p.contact && r.restarts) return smooth_robot(p, r);
  if (!p.contact) {
    return adaptive(p, r, ode::Method::kRadau5, a / 10.0, 7,
                    "smooth (no contact): radau5 with stage Jacobians steps over the stiff modes");
  }
  std::string why;
  const double h = verlet_step(p, r, &why);
  if (h < kVerletMinStep) {
    // A robot's contacts switch at every touchdown and lift-off: RADAU5's Newton iterations
    // stall there (pr_running at 1e7 N/m: 70 000 rejected steps in 1 s, diverged), RODAS4's
    // linearly implicit steps do not (0.40 s per simulated second at 1e7, 0.34 s at 1e8).
    if (r.restarts) {
      return adaptive(p, r, ode::Method::kRodas4, a / 100.0, 4,
                      "verlet would need > 5e4 steps per second, robot contacts switch: stiff, "
                      "linearly implicit, cost flat in k");
    }
    return adaptive(p, r, ode::Method::kRadau5, a / 100.0, 4,
                    "verlet would need > 5e4 steps per second: stiff, cost flat in k");
  }
  return verlet(p, r, h, why.c_str());
}

MethodChoice choose_method(const Mechanism& m, const AutoRequest& request) {
  return choose_method(probe_scene(m), request);
}

bool needs_rerun(const MethodChoice& c, double drift_relative) {
  return c.reruns == 0 && std::isfinite(drift_relative) && drift_relative > c.accuracy;
}

MethodChoice refine_choice(const MethodChoice& c, double drift_relative) {
  constexpr double kAim = 0.5;         // of the accuracy
  constexpr double kMaxFactor = 1e-3;  // the largest tightening at once
  const double f = std::max(kMaxFactor, kAim * c.accuracy / drift_relative);
  MethodChoice r = c;
  r.reruns = c.reruns + 1;
  r.first_drift = drift_relative;
  char buf[200];
  if (c.method == ode::Method::kVerlet && c.energy_tol > 0.0) {
    r.energy_tol = c.energy_tol * f;
    std::snprintf(buf, sizeof buf, "energy_tol %.2g -> %.2g", c.energy_tol, r.energy_tol);
  } else if (c.method == ode::Method::kVerlet) {
    r.h_fixed = round_down_2(c.h_fixed * std::sqrt(f));
    std::snprintf(buf, sizeof buf, "h %.2g -> %.2g s", c.h_fixed, r.h_fixed);
  } else {
    r.rtol = c.rtol * f;
    r.atol = c.atol * f;
    std::snprintf(buf, sizeof buf, "rtol=atol %.2g -> %.2g", c.rtol, r.rtol);
  }
  char head[120];
  std::snprintf(head, sizeof head, "; rerun: the first run drifted %.2g > %.2g, ", drift_relative,
                c.accuracy);
  r.reason += std::string(head) + buf;
  return r;
}

void apply_choice(const MethodChoice& c, ode::SolverOptions* solver, double* energy_tol) {
  solver->method = c.method;
  if (c.method == ode::Method::kVerlet) {
    solver->h_fixed = c.h_fixed;
    solver->h_flight = c.h_flight;
    *energy_tol = c.energy_tol;
  } else {
    solver->rtol = c.rtol;
    solver->atol = c.atol;
  }
}

}  // namespace pronk::pseudorigid
