#include "optimize/sensitivity/design_sensitivity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/robot_settings.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/design_reader.hpp"
#include "optimize/evaluator.hpp"
#include "optimize/parameters.hpp"
#include "optimize/study.hpp"
#include "optimize/study_runner.hpp"

namespace pronk::optimize::sensitivity {

namespace {

using nlohmann::json;

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string dir_of(const std::string& path) {
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// The design's study, in another model when asked.
Study study_of(const RecordedDesign& d, const std::string& path,
               const DesignSensitivityOptions& opt) {
  if (!opt.model) return d.study;
  json doc = d.study.document;
  doc["model"] = *opt.model;
  return parse_study(doc, path + "#/study_document (with --model " + *opt.model + ")",
                     dir_of(path));
}

// The inertia's principal moments, relative ranges r, stay a triangle at every corner.
bool inertia_ok(const double m[3], const double r[3]) {
  for (int c = 0; c < 3; ++c) {
    const int a = (c + 1) % 3, b = (c + 2) % 3;
    if ((1 - r[a]) * m[a] + (1 - r[b]) * m[b] < (1 + r[c]) * m[c]) return false;
  }
  return true;
}

const char* const kInertia[3] = {"/body/inertia_tensor/0/0", "/body/inertia_tensor/1/1",
                                 "/body/inertia_tensor/2/2"};

// Default ranges of the principal moments shrink until every corner is a valid inertia; a
// range given with --range that breaks it is an error.
void fit_inertia_ranges(const json& doc, std::vector<SensitivityInput>& inputs,
                        const std::vector<std::string>& given) {
  double m[3], r[3] = {0, 0, 0};
  SensitivityInput* in[3] = {nullptr, nullptr, nullptr};
  for (int k = 0; k < 3; ++k) {
    m[k] = io::find_pointer(doc, kInertia[k])->get<double>();
    for (auto& i : inputs)
      if (i.pointer == kInertia[k]) in[k] = &i;
    if (in[k]) r[k] = in[k]->range;
  }
  auto is_given = [&](int k) {
    return std::find(given.begin(), given.end(), kInertia[k]) != given.end();
  };
  for (int iter = 0; iter < 60 && !inertia_ok(m, r); ++iter) {
    for (int k = 0; k < 3; ++k)
      if (in[k] && !is_given(k)) r[k] *= 0.8;
  }
  if (!inertia_ok(m, r)) {
    throw io::InputError("--range", "/body/inertia_tensor",
                         "ranges of the principal moments that keep them a triangle (I_a + I_b "
                         ">= I_c) at every corner",
                         "ranges " + num(r[0]) + ", " + num(r[1]) + ", " + num(r[2]) +
                             " of the moments " + num(m[0]) + ", " + num(m[1]) + ", " + num(m[2]));
  }
  for (int k = 0; k < 3; ++k)
    if (in[k]) in[k]->range = r[k];
}

// A physical number of the scene as an input (checked: a number the model uses).
SensitivityInput physical_input(const json& doc, const std::vector<std::string>& unused,
                                const std::string& pointer, const std::string& name,
                                const std::string& origin) {
  if (const std::string* u = ignored_setting(unused, pointer)) {
    throw io::InputError(origin, pointer, "a number the model uses",
                         "a number that model ignores (" + *u + ")");
  }
  const json* v = io::find_pointer(doc, pointer);
  if (v == nullptr || !v->is_number()) {
    throw io::InputError(
        origin, pointer, "a pointer to a number of the scene (see scene.resolved.json)",
        v == nullptr ? "nothing" + io::resolved_pointer_hint(pointer) : io::describe(*v));
  }
  SensitivityInput in;
  in.name = name;
  in.pointer = pointer;
  in.value = v->get<double>();
  return in;
}

// The tuned parameters, the default physical numbers the model uses, and --range's.
std::vector<SensitivityInput> collect_inputs(const EvaluatorConfig& cfg,
                                             const std::vector<double>& unit, const json& doc,
                                             const scene::Scene& scene0,
                                             const DesignSensitivityOptions& opt) {
  std::vector<SensitivityInput> inputs;
  const std::vector<double> values = physical_values(cfg.parameters, unit);
  for (size_t i = 0; i < cfg.parameters.size(); ++i) {
    inputs.push_back({cfg.parameters[i].name, cfg.parameters[i].pointer, true, values[i]});
  }
  const std::vector<std::string> unused = io::unused_settings(scene0);
  std::vector<std::pair<std::string, std::string>> defaults{{"/body/mass", "mass"}};
  const json& I = doc.at("body").at("inertia_tensor");
  if (I[0][1] == 0.0 && I[0][2] == 0.0 && I[1][2] == 0.0 && I[1][0] == 0.0 && I[2][0] == 0.0 &&
      I[2][1] == 0.0) {  // products of inertia: the diagonal entries are no principal moments
    defaults.push_back({kInertia[0], "inertia_xx"});
    defaults.push_back({kInertia[1], "inertia_yy"});
    defaults.push_back({kInertia[2], "inertia_zz"});
  }
  defaults.push_back({"/pseudo_rigid/leg_stiffness", "leg_stiffness"});
  defaults.push_back({"/pseudo_rigid/friction", "friction"});
  auto find = [&](const std::string& p) {
    return std::find_if(inputs.begin(), inputs.end(),
                        [&](const SensitivityInput& i) { return i.pointer == p; });
  };
  for (const auto& [pointer, name] : defaults) {
    const json* v = io::find_pointer(doc, pointer);
    if (v == nullptr || !v->is_number() || ignored_setting(unused, pointer) != nullptr) continue;
    if (find(pointer) != inputs.end()) continue;  // tuned
    inputs.push_back(physical_input(doc, unused, pointer, name, "default inputs"));
  }
  for (auto& i : inputs) i.range = opt.default_range;
  std::vector<std::string> given;
  for (const auto& [pointer, rel] : opt.ranges) {
    auto it = find(pointer);
    if (it == inputs.end()) {
      inputs.push_back(physical_input(doc, unused, pointer, pointer.substr(1), "--range"));
      it = inputs.end() - 1;
    }
    it->range = rel;
    given.push_back(pointer);
  }
  if (!opt.only.empty()) {
    for (const std::string& pointer : opt.only) {
      if (find(pointer) != inputs.end()) continue;
      inputs.push_back(physical_input(doc, unused, pointer, pointer.substr(1), "--inputs"));
      inputs.back().range = opt.default_range;
    }
    std::vector<SensitivityInput> kept;
    for (const std::string& pointer : opt.only) kept.push_back(*find(pointer));
    inputs = std::move(kept);
  }
  if (find(kInertia[0]) != inputs.end() || find(kInertia[1]) != inputs.end() ||
      find(kInertia[2]) != inputs.end()) {
    fit_inertia_ranges(doc, inputs, given);
  }
  for (auto& i : inputs) {
    const double w = i.value == 0.0 ? i.range : i.range * std::abs(i.value);
    i.lower = i.value - w;
    i.upper = i.value + w;
  }
  return inputs;
}

}  // namespace

namespace {

// The evaluator config of the sensitivity: the study's, with the design bound into the scene
// and each of `inputs` a linear parameter whose bounds hold both its range and the local steps.
EvaluatorConfig input_config(EvaluatorConfig cfg, const json& doc,
                             const std::vector<SensitivityInput>& inputs, double step, int threads,
                             JobFarm* farm) {
  cfg.scene_doc = doc;
  cfg.parameters.clear();
  for (const auto& in : inputs) {
    const double h = (in.value == 0.0 ? step : step * std::abs(in.value)) * 1.01;
    Parameter p;
    p.name = in.name;
    p.pointer = in.pointer;
    p.lower = std::min(in.lower, in.value - h);
    p.upper = std::max(in.upper, in.value + h);
    p.initial = in.value;
    cfg.parameters.push_back(p);
  }
  cfg.threads = farm != nullptr ? 1 : threads;
  cfg.farm = farm;
  return cfg;
}

// Evaluates points (values of the inputs), in chunks for the progress line; the outputs of an
// evaluation that made no valid scene are NaN. Design mode: every input a parameter of one
// evaluator. Plant mode: the tuned inputs are its parameters, the physical ones plant draws
// added to every scenario (the controller keeps the design's numbers), one evaluator per point.
class PointRunner {
 public:
  PointRunner(const EvaluatorConfig& cfg, const json& doc, const DesignSensitivityOptions& opt,
              DesignSensitivity& out)
      : opt_(opt), out_(out), pool_(opt.farm != nullptr ? 1 : opt.threads) {
    std::vector<SensitivityInput> params;
    for (size_t j = 0; j < out.inputs.size(); ++j) {
      if (opt.plant && !out.inputs[j].tuned) {
        physical_.push_back(j);
      } else {
        params.push_back(out.inputs[j]);
        tuned_.push_back(j);
      }
    }
    base_ = input_config(cfg, doc, params, opt.local.step, opt.threads, opt.farm);
    if (physical_.empty()) {
      ev_ = std::make_unique<Evaluator>(base_);
    } else {
      base_.threads = 1;  // the points go in parallel, each point's scenarios serially
    }
  }

  std::vector<std::vector<double>> run(const std::vector<Point>& pts, const std::string& label) {
    std::vector<std::vector<double>> y;
    Progress progress(opt_.progress, label, static_cast<long>(pts.size()));
    // On a farm every point's jobs go out at once: larger chunks keep the ranks busy.
    const size_t chunk =
        (opt_.farm != nullptr ? 64 : 8) * static_cast<size_t>(std::max(1, opt_.threads));
    for (size_t b = 0; b < pts.size(); b += chunk) {
      const std::vector<Point> part(
          pts.begin() + static_cast<long>(b),
          pts.begin() + static_cast<long>(std::min(pts.size(), b + chunk)));
      for (const Evaluation& e : evaluate(part)) y.push_back(outputs(e));
      progress.update(static_cast<long>(y.size()));
    }
    progress.finish();
    out_.evaluations += static_cast<long>(pts.size());
    return y;
  }

  std::vector<Evaluation> evaluate(const std::vector<Point>& pts) {
    if (ev_) {
      std::vector<std::vector<double>> units;
      for (const Point& x : pts) units.push_back(unit(x));
      return ev_->evaluate_full_batch(units);
    }
    std::vector<Evaluation> evs(pts.size());
    auto one = [&](long i) {
      evs[static_cast<size_t>(i)] = plant_point(pts[static_cast<size_t>(i)]);
    };
    if (opt_.farm != nullptr) {  // one farm: a point at a time, its scenarios over the ranks
      for (size_t i = 0; i < pts.size(); ++i) one(static_cast<long>(i));
    } else {
      pool_.parallel_for(static_cast<long>(pts.size()), one);
    }
    return evs;
  }

  /// The output names from the design's own evaluation (which must succeed).
  void name_outputs(const Evaluation& e) {
    out_.outputs = {"cost"};
    for (const auto& [k, v] : e.aggregated) out_.outputs.push_back(k);
  }

 private:
  std::vector<double> unit(const Point& x) const {
    std::vector<double> u;
    for (size_t t = 0; t < tuned_.size(); ++t)
      u.push_back(base_.parameters[t].to_unit(x[tuned_[t]]));
    return u;
  }

  // Plant mode: the physical inputs as draws on every scenario, relative to the design's value
  // (so they compose with the study's own robot perturbations), absolute for a 0.
  Evaluation plant_point(const Point& x) const {
    try {
      EvaluatorConfig cfg = base_;
      std::vector<PlantDraw> draws;
      for (size_t j : physical_) {
        const SensitivityInput& in = out_.inputs[j];
        const bool rel = in.value != 0.0;
        draws.push_back({in.pointer, rel, rel ? x[j] / in.value - 1.0 : x[j]});
      }
      for (Scenario& sc : cfg.scenarios.scenarios) {
        sc.plant.insert(sc.plant.end(), draws.begin(), draws.end());
      }
      return Evaluator(std::move(cfg)).evaluate_full(unit(x));
    } catch (const std::exception& e) {
      Evaluation ev;
      ev.ok = false;
      ev.failure = e.what();
      return ev;
    }
  }

  std::vector<double> outputs(const Evaluation& e) {
    std::vector<double> v(out_.outputs.size(), NAN);
    if (!e.ok) {
      ++out_.failed;
      if (out_.failures.size() < 5) out_.failures.push_back(e.failure);
      return v;
    }
    v[0] = e.cost;
    for (size_t i = 1; i < v.size(); ++i) {
      const auto it = e.aggregated.find(out_.outputs[i]);
      if (it != e.aggregated.end()) v[i] = it->second;
    }
    return v;
  }

  const DesignSensitivityOptions& opt_;
  DesignSensitivity& out_;
  ThreadPool pool_;
  EvaluatorConfig base_;
  std::vector<size_t> tuned_, physical_;  ///< indices into out_.inputs
  std::unique_ptr<Evaluator> ev_;         ///< design mode, or no physical inputs
};

// One at a time: every input at the lower and at the upper end of its range.
void one_at_a_time(PointRunner& runner, DesignSensitivity& out) {
  const size_t k = out.inputs.size();
  std::vector<Point> pts;
  for (size_t j = 0; j < k; ++j) {
    for (double end : {out.inputs[j].lower, out.inputs[j].upper}) {
      Point p = out.local.x0;
      p[j] = end;
      pts.push_back(p);
    }
  }
  const auto y = runner.run(pts, "one-at-a-time evaluations");
  out.low.assign(out.outputs.size(), std::vector<double>(k, NAN));
  out.high = out.low;
  for (size_t j = 0; j < k; ++j) {
    for (size_t i = 0; i < out.outputs.size(); ++i) {
      out.low[i][j] = y[2 * j][i];
      out.high[i][j] = y[2 * j + 1][i];
    }
  }
}

}  // namespace

void DesignSensitivityOptions::validate() const {
  local.validate();
  if (sobol.samples != 0) sobol.validate();
  for (const auto& [pointer, rel] : ranges) {
    if (!(rel > 0.0 && rel < 1.0)) {
      throw io::InputError("--range", pointer, "a relative range in (0, 1), e.g. 0.1", num(rel));
    }
  }
  for (size_t i = 0; i < only.size(); ++i) {
    if (only[i].empty() || only[i][0] != '/') {
      throw io::InputError("--inputs", "", "a JSON Pointer, e.g. /body/mass", "\"" + only[i] + "\"");
    }
    if (std::find(only.begin(), only.begin() + static_cast<long>(i), only[i]) !=
        only.begin() + static_cast<long>(i)) {
      throw io::InputError("--inputs", only[i], "each input once", "it twice");
    }
  }
  for (const auto& r : ranges) {
    if (!only.empty() && std::find(only.begin(), only.end(), r.first) == only.end()) {
      throw io::InputError("--range", r.first, "one of the --inputs",
                           "a pointer --inputs leaves out");
    }
  }
  if (model && *model != "impulse" && *model != "pulse" && *model != "pseudo_rigid") {
    throw io::InputError("--model", "", "impulse, pulse or pseudo_rigid", "\"" + *model + "\"");
  }
}

std::pair<std::string, double> parse_range_option(const std::string& text) {
  const size_t eq = text.rfind('=');
  const std::string expected = "POINTER=REL, e.g. /body/mass=0.1";
  if (eq == std::string::npos || text.empty() || text[0] != '/') {
    throw io::InputError("--range", "", expected, "\"" + text + "\"");
  }
  const std::string value = text.substr(eq + 1);
  char* end = nullptr;
  const double rel = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0') {
    throw io::InputError("--range", text.substr(0, eq), expected, "\"" + text + "\"");
  }
  return {text.substr(0, eq), rel};
}

DesignSensitivity design_sensitivity(const json& design, const std::string& path,
                                     const DesignSensitivityOptions& opt) {
  opt.validate();
  const RecordedDesign d = read_design(design, path);
  const Study st = study_of(d, path, opt);
  DesignSensitivity out;
  out.design_path = path;
  out.study = st.name;
  out.set = opt.validation ? "validation" : "scenarios";
  EvaluatorConfig cfg = st.evaluator;
  if (opt.validation) {
    if (!st.validation) {
      throw io::InputError(path, "/study_document/validation",
                           "a study with a validation set (--validation)", "none");
    }
    cfg = validation_evaluator(st, 1).config();
  }
  out.scenarios = static_cast<long>(cfg.scenarios.scenarios.size());
  const json doc = bind_parameters(cfg.scene_doc, cfg.parameters, d.unit);
  const scene::Scene scene0 = io::parse_scene(doc, cfg.scene_file);
  out.model = std::string(scene::to_string(scene0.model));
  out.inputs = collect_inputs(cfg, d.unit, doc, scene0, opt);
  PointRunner runner(cfg, doc, opt, out);
  std::vector<double> x0;
  for (const auto& in : out.inputs) x0.push_back(in.value);
  const Evaluation e0 = runner.evaluate({x0}).front();
  if (!e0.ok) {
    throw io::InputError(path, "/unit",
                         "a design that makes a valid scene in the " + out.model + " model",
                         e0.failure);
  }
  runner.name_outputs(e0);

  auto t0 = std::chrono::steady_clock::now();
  progress_note(opt.progress, "local derivatives: " + std::to_string(4 * x0.size() + 1) +
                                  " evaluations, " + std::to_string(out.inputs.size()) + " inputs");
  out.local = local_from_outputs(x0, opt.local,
                                 runner.run(local_points(x0, opt.local), "local evaluations"));
  one_at_a_time(runner, out);
  out.local_seconds = seconds_since(t0);
  out.local_step = opt.local.step;
  out.plant = opt.plant;
  out.sobol_options = opt.sobol;
  if (opt.sobol.samples > 0) {
    t0 = std::chrono::steady_clock::now();
    std::vector<double> lo, hi;
    for (const auto& in : out.inputs) {
      lo.push_back(in.lower);
      hi.push_back(in.upper);
    }
    const std::vector<Point> pts = saltelli_points(lo, hi, opt.sobol);
    progress_note(opt.progress, "Sobol indices: " + std::to_string(pts.size()) + " evaluations");
    out.sobol = sobol_from_outputs(lo.size(), opt.sobol, runner.run(pts, "Sobol evaluations"));
    out.sobol_seconds = seconds_since(t0);
  }
  return out;
}

}  // namespace pronk::optimize::sensitivity
