#include "optimize/pareto/moo_options.hpp"

#include <pagmo/algorithms/moead.hpp>
#include <pagmo/algorithms/nsga2.hpp>
#include <pagmo/algorithms/nspso.hpp>
#include <pagmo/utils/multi_objective.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <random>
#include <sstream>

#include "optimize/pareto/moo_algorithm.hpp"

namespace pronk::optimize::pareto {

namespace {

enum class Kind { kNumber, kInteger, kBoolean, kWord };

/// One option of an algorithm: its kind, range or words, and pagmo's default.
struct OptionRule {
  const char* name;
  Kind kind;
  double lo = 0.0, hi = 0.0;
  bool lo_open = false, hi_open = false;  ///< (lo, ...] or [..., hi)
  double fallback = 0.0;                  ///< numbers and booleans (1 = true)
  std::vector<std::string> words = {};    ///< kWord: the allowed words, the default first
};

struct AlgorithmSpec {
  const char* name;
  std::vector<OptionRule> options;
};

/// pagmo 2.18's constructors and checks (src/algorithms/{nsga2,moead,nspso}.cpp).
const std::vector<AlgorithmSpec>& specs() {
  static const std::vector<AlgorithmSpec> table = {
      {"nsga2",
       {{"cr", Kind::kNumber, 0, 1, false, true, 0.95},
        {"eta_c", Kind::kNumber, 1, 100, false, false, 10},
        {"m", Kind::kNumber, 0, 1, false, false, 0.01},
        {"eta_m", Kind::kNumber, 1, 100, false, false, 50}}},
      {"moead",
       {{"weight_generation", Kind::kWord, 0, 0, false, false, 0, {"grid", "low discrepancy"}},
        {"decomposition", Kind::kWord, 0, 0, false, false, 0, {"tchebycheff", "weighted", "bi"}},
        {"neighbours", Kind::kInteger, 2, 1e6, false, false, 20},
        {"CR", Kind::kNumber, 0, 1, false, false, 1.0},
        {"F", Kind::kNumber, 0, 1, false, false, 0.5},
        {"eta_m", Kind::kNumber, 0, 1e6, false, false, 20},
        {"realb", Kind::kNumber, 0, 1, false, false, 0.9},
        {"limit", Kind::kInteger, 0, 1e6, false, false, 2},
        {"preserve_diversity", Kind::kBoolean, 0, 0, false, false, 1}}},
      {"nspso",
       {{"omega", Kind::kNumber, 0, 1, false, false, 0.6},
        {"c1", Kind::kNumber, 0, 1e6, true, false, 2.0},
        {"c2", Kind::kNumber, 0, 1e6, true, false, 2.0},
        {"chi", Kind::kNumber, 0, 1e6, true, false, 1.0},
        {"v_coeff", Kind::kNumber, 0, 1, true, false, 0.5},
        {"leader_selection_range", Kind::kInteger, 1, 100, false, false, 60},
        {"diversity_mechanism",
         Kind::kWord,
         0,
         0,
         false,
         false,
         0,
         {"crowding distance", "niche count", "max min"}}}},
  };
  return table;
}

const AlgorithmSpec* find_spec(const std::string& name) {
  for (const auto& s : specs())
    if (name == s.name) return &s;
  return nullptr;
}

const OptionRule* find_rule(const AlgorithmSpec& spec, const std::string& name) {
  for (const auto& r : spec.options)
    if (name == r.name) return &r;
  return nullptr;
}

std::string number_text(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

std::string rule_text(const OptionRule& r) {
  switch (r.kind) {
    case Kind::kBoolean:
      return "expected true or false";
    case Kind::kWord: {
      std::string out;
      for (const auto& w : r.words) out += (out.empty() ? "\"" : ", \"") + w + "\"";
      return "expected one of " + out;
    }
    case Kind::kInteger:
      return "expected an integer in [" + number_text(r.lo) + ", " + number_text(r.hi) + "]";
    case Kind::kNumber:
      break;
  }
  return std::string("expected a number in ") + (r.lo_open ? "(" : "[") + number_text(r.lo) + ", " +
         number_text(r.hi) + (r.hi_open ? ")" : "]");
}

/// Whether `v` is a value `r` accepts.
bool accepts(const OptionRule& r, const nlohmann::json& v) {
  if (r.kind == Kind::kBoolean) return v.is_boolean();
  if (r.kind == Kind::kWord)
    return v.is_string() &&
           std::find(r.words.begin(), r.words.end(), v.get<std::string>()) != r.words.end();
  if (!v.is_number() || v.is_boolean()) return false;
  const double x = v.get<double>();
  if (!std::isfinite(x)) return false;
  if (r.kind == Kind::kInteger && x != std::trunc(x)) return false;
  const bool lo_ok = r.lo_open ? x > r.lo : x >= r.lo;
  const bool hi_ok = r.hi_open ? x < r.hi : x <= r.hi;
  return lo_ok && hi_ok;
}

/// The option's value: given (and valid) or pagmo's default, as a double (booleans 0 or 1).
double number(const MooOptions& o, const char* name) {
  const OptionRule* r = find_rule(*find_spec(o.algorithm), name);
  const auto it = o.options.is_object() ? o.options.find(name) : o.options.end();
  if (it != o.options.end() && accepts(*r, *it))
    return it->is_boolean() ? (it->get<bool>() ? 1.0 : 0.0) : it->get<double>();
  return r->fallback;
}

std::string word(const MooOptions& o, const char* name) {
  const OptionRule* r = find_rule(*find_spec(o.algorithm), name);
  const auto it = o.options.is_object() ? o.options.find(name) : o.options.end();
  if (it != o.options.end() && accepts(*r, *it)) return it->get<std::string>();
  return r->words.front();
}

unsigned whole(const MooOptions& o, const char* name) {
  return static_cast<unsigned>(number(o, name));
}

std::string option_list(const AlgorithmSpec& spec) {
  std::string out;
  for (const auto& r : spec.options) out += (out.empty() ? "" : ", ") + std::string(r.name);
  return out;
}

/// The algorithm's own rule on the population size ("" when it holds).
std::string population_rule(const MooOptions& o, long objectives) {
  const long n = o.population;
  if (o.algorithm == "nsga2") {
    if (n < 8 || n % 4 != 0)
      return "expected a multiple of 4 of at least 8 (pagmo's nsga2 needs at least 5 "
             "individuals and a multiple of 4)";
    return "";
  }
  if (o.algorithm == "nspso")
    return n < 2 ? "expected at least 2 (pagmo's nspso needs 2 particles)" : "";
  const long neighbours = static_cast<long>(whole(o, "neighbours"));
  if (n < neighbours + 1)
    return "expected at least neighbours + 1 = " + std::to_string(neighbours + 1) +
           " (pagmo's moead: a weight's neighbourhood excludes itself)";
  if (n < objectives)
    return "expected at least the objective count " + std::to_string(objectives) +
           " (pagmo's moead: one weight per objective's corner)";
  try {
    std::mt19937 unused;
    (void)pagmo::decomposition_weights(static_cast<std::size_t>(objectives),
                                       static_cast<std::size_t>(n), word(o, "weight_generation"),
                                       unused);
  } catch (const std::exception& e) {
    return "expected a population the \"" + word(o, "weight_generation") + "\" weights of " +
           std::to_string(objectives) + " objectives allow (pagmo says: " + e.what() + ")";
  }
  return "";
}

std::string entries(std::size_t n) { return std::to_string(n) + (n == 1 ? " entry" : " entries"); }

/// options/NAME: every given option known and valid.
void check_algorithm_options(const MooOptions& o, const AlgorithmSpec& spec,
                             std::vector<std::string>* errors) {
  if (!o.options.is_object()) {
    errors->push_back("options: " + o.options.dump() + ": expected an object");
    return;
  }
  for (auto it = o.options.begin(); it != o.options.end(); ++it) {
    const OptionRule* r = find_rule(spec, it.key());
    if (r == nullptr)
      errors->push_back("options/" + it.key() + ": an unknown option: expected an option of " +
                        spec.name + " (" + option_list(spec) + ")");
    else if (!accepts(*r, it.value()))
      errors->push_back("options/" + it.key() + ": " + it.value().dump() + ": " + rule_text(*r));
  }
}

void check_reference(const MooOptions& o, long objectives, std::vector<std::string>* errors) {
  if (o.reference.empty()) return;
  if (static_cast<long>(o.reference.size()) != objectives && objectives >= 2)
    errors->push_back("reference: " + entries(o.reference.size()) + ": expected " +
                      std::to_string(objectives) + ", one per objective");
  for (double r : o.reference)
    if (!std::isfinite(r)) {
      errors->push_back("reference: " + number_text(r) + ": expected finite values");
      break;
    }
}

}  // namespace

const std::vector<std::string>& moo_algorithm_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& s : specs()) v.emplace_back(s.name);
    return v;
  }();
  return names;
}

std::vector<std::string> MooOptions::validate(long objectives) const {
  std::vector<std::string> errors;
  if (objectives < 2)
    errors.push_back("objectives: " + entries(static_cast<std::size_t>(std::max(0L, objectives))) +
                     ": a multi-objective algorithm needs at least 2");
  if (generations < 1 || generations > 100000000)
    errors.push_back("generations: " + std::to_string(generations) +
                     ": expected an integer in [1, 100000000]");
  check_reference(*this, objectives, &errors);
  const AlgorithmSpec* spec = find_spec(algorithm);
  if (spec == nullptr) {
    std::string names;
    for (const auto& n : moo_algorithm_names()) names += (names.empty() ? "" : ", ") + n;
    errors.push_back("algorithm: \"" + algorithm +
                     "\": expected a multi-objective algorithm pronk offers (" + names + ")");
    return errors;
  }
  check_algorithm_options(*this, *spec, &errors);
  if (population < 1 || population > 1000000) {
    errors.push_back("population: " + std::to_string(population) +
                     ": expected an integer in [1, 1000000]");
  } else if (objectives >= 2) {
    const std::string rule = population_rule(*this, objectives);
    if (!rule.empty()) errors.push_back("population: " + std::to_string(population) + ": " + rule);
  }
  if (!errors.empty()) return errors;
  // pagmo's own constructor checks, in case this table and pagmo ever disagree.
  try {
    (void)detail::make_moo_algorithm(*this, 0u, nullptr);
  } catch (const std::exception& e) {
    errors.push_back("algorithm: \"" + algorithm +
                     "\": expected options pagmo accepts (pagmo says: " + e.what() + ")");
  }
  return errors;
}

namespace detail {

bool moo_native_batch(const MooOptions& o) { return o.algorithm != "moead"; }

pagmo::algorithm make_moo_algorithm(const MooOptions& o, unsigned seed, const pagmo::bfe* batch) {
  if (o.algorithm == "nsga2") {
    pagmo::nsga2 a(1u, number(o, "cr"), number(o, "eta_c"), number(o, "m"), number(o, "eta_m"),
                   seed);
    if (batch != nullptr) a.set_bfe(*batch);
    return pagmo::algorithm(std::move(a));
  }
  if (o.algorithm == "moead")
    return pagmo::algorithm(pagmo::moead(1u, word(o, "weight_generation"), word(o, "decomposition"),
                                         whole(o, "neighbours"), number(o, "CR"), number(o, "F"),
                                         number(o, "eta_m"), number(o, "realb"), whole(o, "limit"),
                                         number(o, "preserve_diversity") != 0.0, seed));
  if (o.algorithm == "nspso") {
    // memory = true: one evolve() per generation continues the same swarm.
    pagmo::nspso a(1u, number(o, "omega"), number(o, "c1"), number(o, "c2"), number(o, "chi"),
                   number(o, "v_coeff"), whole(o, "leader_selection_range"),
                   word(o, "diversity_mechanism"), true, seed);
    if (batch != nullptr) a.set_bfe(*batch);
    return pagmo::algorithm(std::move(a));
  }
  throw std::invalid_argument("unknown multi-objective algorithm '" + o.algorithm + "'");
}

}  // namespace detail

}  // namespace pronk::optimize::pareto
