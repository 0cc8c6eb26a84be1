#include "optimize/perturbation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/parameters.hpp"
#include "optimize/scenario.hpp"

namespace pronk::optimize {

using nlohmann::json;

namespace {

constexpr const char* kTensor = "/body/inertia_tensor";

bool under(const std::string& p, const std::string& prefix) { return pointer_under(p, prefix); }

// A number that only makes sense positive: a mass, an inertia, a stiffness.
bool must_be_positive(const std::string& pointer) {
  const std::string last = pointer.substr(pointer.rfind('/') + 1);
  return under(pointer, kTensor) || last.find("mass") != std::string::npos ||
         last.find("stiffness") != std::string::npos;
}

std::string num(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

std::string range_text(double lo, double hi) { return "[" + num(lo) + ", " + num(hi) + "]"; }

// The value at one end of the range (relative ones on the nominal value).
double end_value(const PlantPerturbation& p, double nominal, bool high) {
  const double d = high ? p.hi : p.lo;
  return p.relative ? nominal * (1.0 + d) : d;
}

// The pointer names a number of the resolved scene that the model uses; the inertia as a
// whole, or a principal moment of a diagonal tensor. Returns its nominal value (1 for the
// whole tensor: a scale).
double check_pointer(io::JsonReader& e, const PlantPerturbation& p, const PerturbationContext& c) {
  const json& resolved = *c.resolved;
  const json* target = p.pointer.empty() ? nullptr : io::find_pointer(resolved, p.pointer);
  const bool tensor = p.pointer == kTensor;
  if (target == nullptr || !(target->is_number() || tensor)) {
    throw e.error("pointer",
                  "a pointer to a number of the scene (see scene.resolved.json), or " +
                      std::string(kTensor) + " for the whole inertia",
                  "\"" + p.pointer + "\", which names " +
                      (target == nullptr ? "nothing" + io::resolved_pointer_hint(p.pointer)
                                         : io::describe(*target)));
  }
  if (const std::string* u = ignored_setting(c.unused, p.pointer)) {
    throw e.error("pointer",
                  "a number the " + std::string(scene::to_string(c.model)) + " model uses",
                  "\"" + p.pointer + "\", which that model ignores (" + *u + ")");
  }
  if (under(p.pointer, kTensor) && !tensor) {
    const json& I = resolved.at("body").at("inertia_tensor");
    const std::string rest = p.pointer.substr(std::string(kTensor).size() + 1);
    bool diagonal_tensor = true;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i != j && I[i][j].get<double>() != 0.0) diagonal_tensor = false;
    const bool diagonal_entry = rest.size() == 3 && rest[0] == rest[2] && rest[1] == '/';
    if (!diagonal_entry || !diagonal_tensor) {
      throw e.error("pointer",
                    "a principal moment of a diagonal inertia (" + std::string(kTensor) +
                        "/k/k) or the whole inertia (" + kTensor + ", relative)",
                    "\"" + p.pointer + "\"" +
                        (diagonal_entry ? ", on a tensor with products of inertia"
                                        : ", a product of inertia"));
    }
  }
  return tensor ? 1.0 : target->get<double>();
}

// The range: exactly one of "relative" and "range", [lo, hi] with lo <= hi.
void read_range(io::JsonReader& e, PlantPerturbation& p) {
  if (e.has("relative") == e.has("range")) {
    throw e.error("relative", "exactly one of \"relative\" ([lo, hi] fractions) and \"range\"",
                  e.has("range") ? "both" : "neither");
  }
  p.relative = e.has("relative");
  const std::string key = p.relative ? "relative" : "range";
  const Eigen::VectorXd v = e.vector(key, 2);
  if (!(v[0] <= v[1])) throw e.error(key, "[lo, hi] with lo <= hi", range_text(v[0], v[1]));
  if (p.relative && !(v[0] > -1.0)) {
    throw e.error(key, "fractions above -1 (a relative range keeps the sign of the number)",
                  range_text(v[0], v[1]));
  }
  if (!p.relative && p.pointer == kTensor) {
    throw e.error("range", "\"relative\" for the whole inertia (it scales the tensor)",
                  "an absolute range");
  }
  p.lo = v[0];
  p.hi = v[1];
  e.optional(p.relative ? "range" : "relative");
}

void read_distribution(io::JsonReader& e, PlantPerturbation& p) {
  p.normal = e.choice_or("distribution", "uniform", {"uniform", "normal"}) == "normal";
  if (!p.normal) {
    if (e.has("sigma"))
      throw e.error("sigma", "no \"sigma\" for a uniform distribution", "a sigma");
    e.optional("sigma");
    return;
  }
  const double width = p.hi - p.lo;
  if (!e.has("sigma")) throw e.error("sigma", "the normal's standard deviation", "nothing");
  p.sigma = e.number("sigma");
  if (!(p.sigma > 0.0 && p.sigma <= width)) {
    throw e.error("sigma",
                  "0 < sigma <= hi - lo = " + num(width) +
                      " (the normal is truncated to the range; a wider one is a uniform)",
                  num(p.sigma));
  }
}

// Each end of the range gives a valid scene with a positive mass, inertia or stiffness.
void check_ends(io::JsonReader& e, const PlantPerturbation& p, double nominal,
                const PerturbationContext& c) {
  const std::string key = p.relative ? "relative" : "range";
  if (p.relative && nominal == 0.0) {
    throw e.error(key, "a number that is not 0 (a relative range of 0 changes nothing)",
                  "\"" + p.pointer + "\" = 0 in the scene");
  }
  for (bool high : {false, true}) {
    const double v = end_value(p, nominal, high);
    const std::string at = "at the " + std::string(high ? "upper" : "lower") + " end of " +
                           range_text(p.lo, p.hi) + ", " + p.pointer + " = " + num(v);
    if (must_be_positive(p.pointer) && !(v > 0.0))
      throw e.error(key, "a range that keeps " + p.pointer + " > 0", at);
    if (under(p.pointer, kTensor)) continue;  // the inertia: jointly, check_inertia_corners
    try {
      io::parse_scene(
          perturbed_document(*c.resolved, {{p.pointer, p.relative, high ? p.hi : p.lo}}),
          c.scene_file);
    } catch (const io::InputError& err) {
      throw e.error(key, "a range whose every value gives a valid scene",
                    at + ": the scene wants " + err.expected() + " at " + err.pointer() +
                        ", found " + err.found());
    }
  }
}

// The inertia perturbations jointly: every corner of their ranges gives principal moments that
// are positive and satisfy the triangle inequality. Both are checked exactly by the corners:
// the diagonal is linear in the draws, so the largest moment minus the sum of the others is
// largest, and the smallest moment smallest, at a corner.
void check_inertia_corners(io::JsonReader& list, const std::vector<PlantPerturbation>& all,
                           const std::vector<size_t>& inertia, const PerturbationContext& c) {
  const size_t n = inertia.size();
  for (unsigned corner = 0; corner < (1u << n); ++corner) {
    std::vector<PlantDraw> draws;
    std::string where;
    for (size_t b = 0; b < n; ++b) {
      const PlantPerturbation& p = all[inertia[b]];
      const bool high = ((corner >> b) & 1u) != 0;
      draws.push_back({p.pointer, p.relative, high ? p.hi : p.lo});
      where += (where.empty() ? "" : ", ") + p.pointer +
               (high ? " at its upper end" : " at its lower end");
    }
    try {
      io::parse_scene(perturbed_document(*c.resolved, draws), c.scene_file);
    } catch (const io::InputError& err) {
      throw list.error("perturb",
                       "inertia ranges whose every corner gives positive principal moments that "
                       "satisfy the triangle inequality (each <= the sum of the other two)",
                       where + ": " + err.found());
    }
  }
}

}  // namespace

std::vector<PlantPerturbation> parse_perturbations(io::JsonReader& random,
                                                   const PerturbationContext& c) {
  std::vector<PlantPerturbation> out;
  if (!random.has("perturb")) {
    random.optional("perturb");
    return out;
  }
  std::vector<size_t> inertia;
  for (io::JsonReader e : random.object_array("perturb")) {
    PlantPerturbation p;
    p.pointer = e.string_or("pointer", "");
    const double nominal = check_pointer(e, p, c);
    for (const auto& q : out) {
      if (under(p.pointer, q.pointer) || under(q.pointer, p.pointer))
        throw e.error("pointer", "each number perturbed once", "\"" + p.pointer + "\" again");
    }
    read_range(e, p);
    read_distribution(e, p);
    e.finish();
    check_ends(e, p, nominal, c);
    if (under(p.pointer, kTensor)) inertia.push_back(out.size());
    out.push_back(p);
  }
  check_inertia_corners(random, out, inertia, c);
  return out;
}

PlantDraw draw_perturbation(const PlantPerturbation& p, std::uint64_t scenario_seed, long k) {
  SplitMix64 g(mix_seed(scenario_seed, 0x7065727475726200ULL + static_cast<std::uint64_t>(k)));
  double v = g.uniform(p.lo, p.hi);
  if (p.normal) {
    // Box-Muller, rejected outside the range (sigma <= hi - lo: accepted with probability
    // >= 0.38 per try); the bound on tries only guards the loop.
    const double mean = 0.5 * (p.lo + p.hi);
    v = mean;
    for (int tries = 0; tries < 10000; ++tries) {
      const double u1 = 1.0 - g.uniform(), u2 = g.uniform();
      const double x = mean + p.sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
      if (x >= p.lo && x <= p.hi) {
        v = x;
        break;
      }
    }
  }
  return {p.pointer, p.relative, v};
}

json perturbed_document(const json& resolved, const std::vector<PlantDraw>& draws) {
  json doc = resolved;
  for (const PlantDraw& d : draws) {
    if (d.pointer == kTensor) {
      for (auto& row : doc["body"]["inertia_tensor"])
        for (auto& x : row) x = x.get<double>() * (1.0 + d.value);
      continue;
    }
    json& target = doc[json::json_pointer(d.pointer)];
    target = d.relative ? target.get<double>() * (1.0 + d.value) : d.value;
  }
  return doc;
}

scene::Scene perturbed_scene(const scene::Scene& nominal, const std::vector<PlantDraw>& draws) {
  json doc = io::scene_to_json(nominal);
  io::add_defaulted_settings(&doc);  // (actuator_gain, the sensor bias: drawn like any number)
  scene::Scene plant = io::parse_scene(perturbed_document(doc, draws), "perturbed scene");
  plant.controller_model = scene::controller_model_of(nominal);
  return plant;
}

}  // namespace pronk::optimize
