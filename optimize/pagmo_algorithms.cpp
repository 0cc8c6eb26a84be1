#include "optimize/pagmo_algorithms.hpp"

#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/de1220.hpp>
#include <pagmo/algorithms/pso_gen.hpp>
#include <pagmo/algorithms/sade.hpp>
#include <pagmo/algorithms/xnes.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <limits>
#include <sstream>

namespace pronk::optimize::detail {

namespace {

constexpr double kAuto = std::numeric_limits<double>::quiet_NaN();

/// One numeric option of an algorithm: its range and pagmo's default.
struct OptionRule {
  const char* name;
  double lo, hi;
  bool lo_open;     ///< (lo, hi] rather than [lo, hi]
  bool integer;     ///< a whole number
  double fallback;  ///< pagmo's default; NaN: pagmo chooses it (written -1 to pagmo)
};

struct AlgorithmSpec {
  const char* name;
  long min_population;  ///< what pagmo's evolve() requires
  bool tolerances;      ///< takes ftol and xtol
  std::vector<OptionRule> options;
};

/// pagmo 2.18's constructors and checks (include/pagmo/algorithms/*.hpp, src/algorithms/*.cpp).
const std::vector<AlgorithmSpec>& specs() {
  static const std::vector<AlgorithmSpec> table = {
      {"cmaes",
       5,
       true,
       {{"sigma0", 0, 1, true, false, 0.5},
        {"cc", 0, 1, false, false, kAuto},
        {"cs", 0, 1, false, false, kAuto},
        {"c1", 0, 1, false, false, kAuto},
        {"cmu", 0, 1, false, false, kAuto}}},
      {"xnes",
       5,
       true,
       {{"sigma0", 0, 1, true, false, kAuto},
        {"eta_mu", 0, 1, true, false, kAuto},
        {"eta_sigma", 0, 1, true, false, kAuto},
        {"eta_b", 0, 1, true, false, kAuto}}},
      {"de",
       5,
       true,
       {{"F", 0, 1, false, false, 0.8},
        {"CR", 0, 1, false, false, 0.9},
        {"variant", 1, 10, false, true, 2}}},
      {"sade",
       7,
       true,
       {{"variant", 1, 18, false, true, 2}, {"variant_adptv", 1, 2, false, true, 1}}},
      {"de1220", 7, true, {{"variant_adptv", 1, 2, false, true, 1}}},
      {"pso_gen",
       2,
       false,
       {{"omega", 0, 1, false, false, 0.7298},
        {"eta1", 0, 4, false, false, 2.05},
        {"eta2", 0, 4, false, false, 2.05},
        {"max_vel", 0, 1, true, false, 0.5},
        {"variant", 1, 6, false, true, 5},
        {"neighb_type", 1, 4, false, true, 2},
        {"neighb_param", 1, 1000000, false, true, 4}}},
  };
  return table;
}

const AlgorithmSpec* find_spec(const std::string& name) {
  for (const auto& s : specs())
    if (name == s.name) return &s;
  return nullptr;
}

bool fail(std::string* error, const std::string& field, const std::string& value,
          const std::string& rule) {
  if (error != nullptr) *error = field + ": " + value + ": " + rule;
  return false;
}

std::string number_text(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

std::string range_text(const OptionRule& r) {
  if (r.integer) return "an integer in [" + number_text(r.lo) + ", " + number_text(r.hi) + "]";
  return std::string("a number in ") + (r.lo_open ? "(" : "[") + number_text(r.lo) + ", " +
         number_text(r.hi) + "]";
}

/// The options an algorithm accepts, for messages.
std::string option_list(const AlgorithmSpec& spec) {
  std::string out = "population, generations";
  if (spec.tolerances) out += ", ftol, xtol";
  if (std::string(spec.name) == "de1220") out += ", allowed_variants";
  for (const auto& r : spec.options) out += std::string(", ") + r.name;
  return out;
}

/// A number within [lo, hi] (an integer when asked); false with the error otherwise.
bool read_number(const nlohmann::json& v, const std::string& field, const OptionRule& rule,
                 double* out, std::string* error) {
  if (!v.is_number()) return fail(error, field, v.dump(), "expected " + range_text(rule));
  const double x = v.get<double>();
  const bool whole = v.is_number_integer() || (std::isfinite(x) && x == std::trunc(x));
  const bool low_ok = rule.lo_open ? x > rule.lo : x >= rule.lo;
  if (!std::isfinite(x) || !low_ok || x > rule.hi || (rule.integer && !whole))
    return fail(error, field, v.dump(), "expected " + range_text(rule));
  *out = x;
  return true;
}

bool read_allowed_variants(const nlohmann::json& v, PagmoSettings* s, std::string* error) {
  const std::string field = "options/allowed_variants";
  const std::string rule = "expected a non-empty array of distinct integers in [1, 18]";
  if (!v.is_array() || v.empty()) return fail(error, field, v.dump(), rule);
  s->allowed_variants.clear();
  for (const auto& e : v) {
    double x = 0.0;
    if (!read_number(e, field, {"", 1, 18, false, true, 0}, &x, error))
      return fail(error, field, v.dump(), rule);
    const auto u = static_cast<unsigned>(x);
    if (std::find(s->allowed_variants.begin(), s->allowed_variants.end(), u) !=
        s->allowed_variants.end())
      return fail(error, field, v.dump(), rule);
    s->allowed_variants.push_back(u);
  }
  return true;
}

/// The options every algorithm shares: population, generations and the tolerances.
bool read_common(const AlgorithmSpec& spec, const std::string& key, const nlohmann::json& v,
                 PagmoSettings* s, std::string* error, bool* known) {
  *known = true;
  double x = 0.0;
  const std::string field = "options/" + key;
  if (key == "population") {
    if (!read_number(v, field, {"", 1, 1000000, false, true, 0}, &x, error)) return false;
    s->population = static_cast<long>(x);
  } else if (key == "generations") {
    if (!read_number(v, field, {"", 1, 100000000, false, true, 0}, &x, error)) return false;
    s->generations = static_cast<long>(x);
  } else if (spec.tolerances && (key == "ftol" || key == "xtol")) {
    if (!read_number(v, field, {"", 0, 1e12, false, false, 0}, &x, error)) return false;
    (key == "ftol" ? s->ftol : s->xtol) = x;
  } else {
    *known = false;
  }
  return true;
}

double option_or(const PagmoSettings& s, const OptionRule& r) {
  const auto it = s.numbers.find(r.name);
  if (it != s.numbers.end()) return it->second;
  return std::isnan(r.fallback) ? -1.0 : r.fallback;
}

double value(const PagmoSettings& s, const char* name) {
  for (const auto& r : find_spec(s.algorithm)->options)
    if (std::string(r.name) == name) return option_or(s, r);
  return -1.0;
}

unsigned whole(const PagmoSettings& s, const char* name) {
  return static_cast<unsigned>(value(s, name));
}

/// The smallest population the algorithm runs with these options, and why.
long min_population(const AlgorithmSpec& spec, const PagmoSettings& s, std::string* why) {
  *why = "pagmo " + std::string(spec.name) + " needs at least " +
         std::to_string(spec.min_population) + " individuals";
  long need = spec.min_population;
  if (s.algorithm == "pso_gen" && whole(s, "neighb_type") == 2u) {
    // The ring topology links neighb_param / 2 particles on each side of a particle.
    const long radius = static_cast<long>(whole(s, "neighb_param")) / 2;
    if (radius + 1 > need) {
      need = radius + 1;
      *why = "the ring topology of pso_gen (neighb_type 2) links neighb_param / 2 = " +
             std::to_string(radius) + " particles on each side";
    }
  }
  return need;
}

}  // namespace

const std::vector<std::string>& pagmo_algorithm_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& s : specs()) v.emplace_back(s.name);
    return v;
  }();
  return names;
}

bool parse_pagmo_settings(const std::string& algorithm, const nlohmann::json& options,
                          long max_evaluations, PagmoSettings* s, std::string* error) {
  const AlgorithmSpec* spec = find_spec(algorithm);
  if (spec == nullptr) {
    std::string names;
    for (const auto& n : pagmo_algorithm_names()) names += (names.empty() ? "" : ", ") + n;
    std::string rule = "expected a pagmo algorithm pronk offers (" + names + ")";
    if (algorithm == "pso")
      rule +=
          "; pagmo's pso moves one particle at a time and cannot evaluate a swarm as a "
          "batch, pso_gen is its generational form";
    return fail(error, "algorithm", "\"" + algorithm + "\"", rule);
  }
  *s = PagmoSettings{};
  s->algorithm = algorithm;
  if (!options.is_object()) return fail(error, "options", options.dump(), "expected an object");
  for (auto it = options.begin(); it != options.end(); ++it) {
    const std::string& key = it.key();
    bool known = false;
    if (!read_common(*spec, key, it.value(), s, error, &known)) return false;
    if (known) continue;
    if (algorithm == "de1220" && key == "allowed_variants") {
      if (!read_allowed_variants(it.value(), s, error)) return false;
      continue;
    }
    const auto rule = std::find_if(spec->options.begin(), spec->options.end(),
                                   [&](const OptionRule& r) { return key == r.name; });
    if (rule == spec->options.end())
      return fail(error, "options/" + key, "an unknown option",
                  "expected an option of pagmo " + algorithm + " (" + option_list(*spec) + ")");
    double x = 0.0;
    if (!read_number(it.value(), "options/" + key, *rule, &x, error)) return false;
    s->numbers[key] = x;
  }
  if (algorithm == "de1220" && s->allowed_variants.empty())
    s->allowed_variants = {2u, 3u, 7u, 10u, 13u, 14u, 15u, 16u};
  std::string why;
  const long need = min_population(*spec, *s, &why);
  if (s->population < need)
    return fail(error, "options/population", std::to_string(s->population),
                "expected a population of at least " + std::to_string(need) + " (" + why + ")");
  if (s->population > max_evaluations)
    return fail(error, "options/population", std::to_string(s->population),
                "expected at most max_evaluations = " + std::to_string(max_evaluations) +
                    " (the first population alone takes that many evaluations)");
  // pagmo's own constructor checks, in case this table and pagmo ever disagree.
  try {
    (void)make_pagmo_algorithm(*s, 1u, 0u, nullptr);
  } catch (const std::exception& e) {
    return fail(error, "algorithm", "\"" + algorithm + "\"",
                std::string("expected options pagmo accepts (pagmo says: ") + e.what() + ")");
  }
  return true;
}

bool pagmo_native_batch(const PagmoSettings& s) { return s.algorithm == "pso_gen"; }

bool pagmo_independent_generation(const PagmoSettings& s) {
  if (s.algorithm != "sade" && s.algorithm != "de1220") return true;
  return whole(s, "variant_adptv") != 2u;
}

pagmo::algorithm make_pagmo_algorithm(const PagmoSettings& s, unsigned generations, unsigned seed,
                                      const pagmo::bfe* batch) {
  // Tolerances 0: pagmo's own exits never fire (the driver tests ftol and xtol per generation).
  const std::string& a = s.algorithm;
  if (a == "cmaes")
    return pagmo::algorithm(pagmo::cmaes(generations, value(s, "cc"), value(s, "cs"),
                                         value(s, "c1"), value(s, "cmu"), value(s, "sigma0"), 0.0,
                                         0.0, true, true, seed));
  if (a == "xnes")
    return pagmo::algorithm(pagmo::xnes(generations, value(s, "eta_mu"), value(s, "eta_sigma"),
                                        value(s, "eta_b"), value(s, "sigma0"), 0.0, 0.0, true, true,
                                        seed));
  if (a == "de")
    return pagmo::algorithm(
        pagmo::de(generations, value(s, "F"), value(s, "CR"), whole(s, "variant"), 0.0, 0.0, seed));
  if (a == "sade")
    return pagmo::algorithm(pagmo::sade(generations, whole(s, "variant"), whole(s, "variant_adptv"),
                                        0.0, 0.0, true, seed));
  if (a == "de1220")
    return pagmo::algorithm(pagmo::de1220(generations, s.allowed_variants,
                                          whole(s, "variant_adptv"), 0.0, 0.0, true, seed));
  if (a == "pso_gen") {
    pagmo::pso_gen p(generations, value(s, "omega"), value(s, "eta1"), value(s, "eta2"),
                     value(s, "max_vel"), whole(s, "variant"), whole(s, "neighb_type"),
                     whole(s, "neighb_param"), false, seed);
    if (batch != nullptr) p.set_bfe(*batch);
    return pagmo::algorithm(std::move(p));
  }
  throw std::invalid_argument("unknown pagmo algorithm '" + a + "'");
}

}  // namespace pronk::optimize::detail
