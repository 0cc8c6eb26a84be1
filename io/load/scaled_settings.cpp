#include "io/load/scaled_settings.hpp"

#include <sstream>

namespace pronk::io {

namespace {

std::string short_number(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

constexpr const char* kResponseChannels = "x, y, roll, pitch, yaw";

// The response form's frequencies must be sampled at least twice per period by the strides:
// above that the per-stride poles alias to a slower response than the one asked for.
void check_sampled(const scene::RelativeGains& g, double period, const std::string& file) {
  for (int c = 0; c < 5; ++c) {
    const double limit = scene::max_natural_frequency(g.damping_ratio[c], period);
    if (g.natural_frequency[c] >= limit) {
      throw InputError(
          file, "/controller/gains/natural_frequency/" + std::to_string(c),
          "a natural frequency below pi / (T sqrt(1 - zeta^2)) = " + short_number(limit) +
              " rad/s (damping ratio " + short_number(g.damping_ratio[c]) +
              ", stride period T = " + short_number(period) + " s: one sample per stride)",
          "number " + short_number(g.natural_frequency[c]));
    }
  }
}

// The body controller's gains: relative ones turned absolute; a legged robot's roll channel
// and banking, where the scene leaves them out, from the lateral loop placed on its stride.
void resolve_controller(const GivenSettings& given, const std::string& file, scene::Scene* s) {
  scene::Controller& c = s->controller;
  if (given.gains) {
    if (given.gains->form == scene::RelativeGains::Form::kResponse)
      check_sampled(*given.gains, scene::design_stride(*s).period(), file);
    scene::absolute_gains(*given.gains, *s, &c.kp, &c.kd);
  }
  if (s->legs.body_only) return;
  const double ixx = s->body.inertia(0, 0);
  const bool roll_default = !given.gains && !given.kp && !given.kd;
  scene::LateralLoop placed;
  if (!given.gains && (!given.kp || !given.kd)) {
    placed = scene::default_lateral_loop(*s);
    if (!given.kp) c.kp[3] = placed.kp_roll * ixx;
    if (!given.kd) c.kd[3] = placed.kd_roll * ixx;
  }
  if (!given.bank) c.bank_enabled = true;
  if (!c.bank_enabled || (given.bank_kp && given.bank_kd)) return;
  const scene::LateralLoop loop =
      roll_default ? placed
                   : scene::best_bank_gains(c.kp[3] / ixx, c.kd[3] / ixx, scene::design_stride(*s),
                                            s->gravity);
  if (!given.bank_kp) c.bank_kp = loop.bank_kp;
  if (!given.bank_kd) c.bank_kd = loop.bank_kd;
}

// A legged robot in the full model runs its fore-aft position loop with the position trim
// (integral action): where the scene gives neither the gains nor the trim, that loop's three
// poles are placed at kPositionPoles on the design stride (the pulse model's PD defaults
// left the tripod and the hexapod falling behind or running ahead within 7 s).
void full_model_position_loop(const GivenSettings& given, scene::Scene* s) {
  if (!scene::is_full_model(s->model) || s->legs.body_only) return;
  if (given.gains || given.kp || given.kd || given.position_trim_gain) return;
  const scene::PositionLoop l = scene::default_position_loop(*s);
  s->controller.kp[0] = l.kp * s->body.mass;
  s->controller.kd[0] = l.kd * s->body.mass;
  s->pseudo_rigid.position_trim_gain = l.trim;
}

// The full model's leg stiffness, stance attitude feedback, feet and their contact damping.
void resolve_full_model(const GivenSettings& given, scene::Scene* s) {
  scene::PseudoRigid& p = s->pseudo_rigid;
  if (!given.leg_stiffness) {
    const double ts =
        given.leg_stance_time > 0.0 ? given.leg_stance_time : scene::design_stance_time(*s);
    p.leg_stiffness = scene::leg_stiffness_for_stance(*s, ts);
  }
  if (!given.stance_attitude || given.stance) {
    RelativeStanceGains rel;
    const Eigen::Vector2d kp = scene::default_stance_kp_per_inertia(*s);
    for (int k = 0; k < 2; ++k) {
      rel.kp[k] = kp[k];
      rel.kd[k] = scene::kStanceKdPerInertia[k];
    }
    if (given.stance) rel = *given.stance;
    for (int k = 0; k < 2; ++k) {
      p.stance_kp[k] = rel.kp[k] * s->body.inertia(k, k);
      p.stance_kd[k] = rel.kd[k] * s->body.inertia(k, k);
    }
    if (!given.stance_attitude) p.stance_max_moment = scene::default_stance_max_moment(*s);
  }
  if (!given.leg_damping && !s->legs.body_only) p.leg_damping = scene::default_leg_damping(*s);
  full_model_position_loop(given, s);
  if (!given.foot_mass) p.foot_mass = scene::default_foot_mass(s->body);
  if (!given.contact_damping) p.contact_damping = scene::default_contact_damping(p);
}

}  // namespace

void refuse_both_gain_forms(const JsonReader& r) {
  if (r.has("gains") && (r.has("kp") || r.has("kd"))) {
    throw r.error("gains", "either absolute \"kp\" and \"kd\" or relative \"gains\", not both",
                  std::string("\"gains\" beside \"") + (r.has("kp") ? "kp" : "kd") + "\"");
  }
}

scene::RelativeGains parse_relative_gains(JsonReader g) {
  scene::RelativeGains out;
  const bool per_unit = g.has("kp") || g.has("kd");
  const bool response = g.has("natural_frequency") || g.has("damping_ratio");
  if (per_unit && response) {
    throw g.error(g.has("natural_frequency") ? "natural_frequency" : "damping_ratio",
                  "either kp and kd (per unit mass and inertia) or natural_frequency and "
                  "damping_ratio (stride response), not both",
                  "both forms");
  }
  if (response) {
    out.form = scene::RelativeGains::Form::kResponse;
    for (const char* key : {"natural_frequency", "damping_ratio"}) {
      if (!g.has(key)) {
        throw g.error(key,
                      std::string("5 numbers (") + kResponseChannels + ") beside " +
                          (key[0] == 'n' ? "damping_ratio" : "natural_frequency"),
                      "nothing");
      }
    }
    out.natural_frequency = g.vector("natural_frequency", 5, 1e-9, 1e6);
    out.damping_ratio = g.vector("damping_ratio", 5, 0.0, 100.0);
  } else {
    for (const char* key : {"kp", "kd"}) {
      if (!g.has(key)) {
        throw g.error(key,
                      "6 relative gains (x, y, z per unit mass, roll, pitch, yaw per unit "
                      "inertia), or natural_frequency and damping_ratio",
                      "nothing");
      }
    }
    out.kp = g.vector("kp", 6, 0.0, 1e6);
    out.kd = g.vector("kd", 6, 0.0, 1e6);
  }
  g.finish();
  return out;
}

RelativeStanceGains parse_relative_stance_gains(JsonReader g) {
  RelativeStanceGains out;
  for (const char* key : {"kp", "kd"}) {
    if (!g.has(key)) {
      throw g.error(key, "2 gains per unit inertia (roll, pitch): kp [1/s^2], kd [1/s]", "nothing");
    }
  }
  const Eigen::VectorXd kp = g.vector("kp", 2, 0.0, 1e9);
  const Eigen::VectorXd kd = g.vector("kd", 2, 0.0, 1e9);
  for (int k = 0; k < 2; ++k) out.kp[k] = kp[k], out.kd[k] = kd[k];
  g.finish();
  return out;
}

void resolve_scaled_settings(const GivenSettings& given, const std::string& file, scene::Scene* s) {
  resolve_controller(given, file, s);
  resolve_full_model(given, s);
}

}  // namespace pronk::io
