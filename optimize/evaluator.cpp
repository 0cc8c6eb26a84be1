#include "optimize/evaluator.hpp"

#include <chrono>
#include <exception>
#include <limits>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/evaluator_wire.hpp"
#include "sim/simulate.hpp"

namespace pronk::optimize {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

namespace {

// The scene number a pointer names, with the closed range parse_scene accepts
// for it; nullptr for pointers without a fast path (degrees, nested objects...).
double* fast_field(scene::Scene& s, const std::string& ptr, double* lo, double* hi) {
  const double inf = std::numeric_limits<double>::infinity();
  const double tiny = std::numeric_limits<double>::min();
  for (int i = 0; i < 6; ++i) {
    if (ptr == "/controller/kp/" + std::to_string(i)) {
      *lo = 0.0, *hi = 1e9;
      return &s.controller.kp[i];
    }
    if (ptr == "/controller/kd/" + std::to_string(i)) {
      *lo = 0.0, *hi = 1e9;
      return &s.controller.kd[i];
    }
  }
  if (ptr == "/controller/hop_height") {
    *lo = tiny, *hi = inf;
    return &s.controller.hop_height;
  }
  if (ptr == "/controller/bank/kp" || ptr == "/controller/bank/kd") {
    *lo = 0.0, *hi = 1e6;
    return ptr.back() == 'p' ? &s.controller.bank_kp : &s.controller.bank_kd;
  }
  if (ptr == "/pulse/duration") {
    *lo = tiny, *hi = inf;
    return &s.pulse.duration;
  }
  if (ptr == "/pulse/max_force") {
    *lo = tiny, *hi = inf;
    return &s.pulse.max_force;
  }
  return nullptr;
}

}  // namespace

Evaluator::Evaluator(EvaluatorConfig config)
    : config_(std::move(config)), pool_(std::make_unique<ThreadPool>(config_.threads)) {
  if (config_.farm) farm_id_ = config_.farm->add_config(config_);
  try {
    base_scene_ = io::parse_scene(config_.scene_doc, config_.scene_file);
  } catch (const io::InputError&) {
    return;  // every evaluation takes the JSON path and reports the error
  }
  scene::Scene probe = base_scene_;
  fast_binding_ = true;
  for (const auto& p : config_.parameters) {
    double lo = 0, hi = 0;
    if (fast_field(probe, p.pointer, &lo, &hi) == nullptr || p.lower < lo || p.upper > hi) {
      fast_binding_ = false;
    }
  }
}

std::vector<double> Evaluator::lower_bounds() const {
  return std::vector<double>(dimension(), 0.0);
}
std::vector<double> Evaluator::upper_bounds() const {
  return std::vector<double>(dimension(), 1.0);
}

std::vector<double> Evaluator::initial_point() const {
  std::vector<double> x;
  for (const auto& p : config_.parameters) x.push_back(p.to_unit(p.initial));
  return x;
}

std::vector<std::string> Evaluator::variable_names() const {
  std::vector<std::string> n;
  for (const auto& p : config_.parameters) n.push_back(p.name);
  return n;
}

std::vector<std::string> Evaluator::constraint_names() const {
  std::vector<std::string> n;
  for (const auto& c : config_.constraints) n.push_back(c.label());
  return n;
}

scene::Scene Evaluator::scene_at(const std::vector<double>& unit) const {
  if (fast_binding_) {
    scene::Scene s = base_scene_;
    double lo = 0, hi = 0;
    for (size_t i = 0; i < config_.parameters.size(); ++i) {
      *fast_field(s, config_.parameters[i].pointer, &lo, &hi) =
          config_.parameters[i].from_unit(unit[i]);
    }
    return s;
  }
  return io::parse_scene(bind_parameters(config_.scene_doc, config_.parameters, unit),
                         config_.scene_file);
}

Evaluation Evaluator::evaluate_full(const std::vector<double>& unit) const {
  return evaluate_impl(unit, true);
}

Evaluation Evaluator::evaluate_full(const std::vector<double>& unit,
                                    const std::function<void()>& on_trial) const {
  return evaluate_impl(unit, true, &on_trial);
}

bool Evaluator::bind(const std::vector<double>& unit, Evaluation& ev, scene::Scene& base) const {
  const size_t nc = config_.constraints.size();
  auto fail = [&](std::string why) {
    ev.ok = false;
    ev.failure = std::move(why);
    ev.cost = config_.failure_cost;
    ev.objectives.assign(config_.objectives.size(), config_.failure_cost);
    ev.constraints.assign(nc, config_.failure_cost);
    return false;
  };
  ev.unit = unit;
  ev.values = physical_values(config_.parameters, unit);
  if (static_cast<int>(unit.size()) != dimension()) return fail("wrong number of parameters");
  try {
    base = scene_at(unit);
  } catch (const io::InputError& e) {
    return fail(std::string("invalid scene for these parameters: ") + e.what());
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what());
  }
  return true;
}

JobOutcome Evaluator::run_job(const scene::Scene& base, long job) const {
  JobOutcome out;
  try {
    // Job 0 is the stability analysis (the longest: start it first).
    if (job == 0) {
      if (config_.stability) out.stability = analyze_stability(base);
      return out;
    }
    const Scenario& sc = config_.scenarios.scenarios.at(static_cast<size_t>(job - 1));
    const scene::Scene s = apply_scenario(base, sc, config_.scenarios);
    RunOptions opts;
    opts.record_trajectory = false;
    const RunResult r = simulate(s, opts);
    out.scenario.name = sc.name;
    out.scenario.status = std::string(reduced::to_string(r.run.status));
    out.scenario.reason = r.run.reason;
    out.scenario.metrics = scenario_metrics(s, r, config_.fall_penalty, config_.settle);
    out.scenario.strides = r.run.cost.touchdowns;
  } catch (const std::exception& e) {
    out.error = e.what();
    if (out.error.empty()) out.error = "an exception without a message";
  }
  return out;
}

void Evaluator::finish(Evaluation& ev, const scene::Scene& base,
                       std::vector<JobOutcome>& jobs) const {
  for (const auto& j : jobs) {
    if (!j.error.empty()) {
      ev.ok = false;
      ev.failure = "internal error: " + j.error;
      ev.cost = config_.failure_cost;
      ev.objectives.assign(config_.objectives.size(), config_.failure_cost);
      ev.constraints.assign(config_.constraints.size(), config_.failure_cost);
      return;
    }
  }
  const StabilityEstimate& stab = jobs.front().stability;
  for (size_t i = 1; i < jobs.size(); ++i) {
    ev.strides += jobs[i].scenario.strides;
    ev.scenarios.push_back(std::move(jobs[i].scenario));
  }
  const long n = static_cast<long>(ev.scenarios.size());
  ev.model = base.model;
  ev.simulations = n + (config_.stability ? stab.simulations : 0);
  ev.strides += config_.stability ? stab.strides : 0;
  ev.spectral_radius = config_.stability ? stab.spectral_radius : 0.0;
  ev.stability_reason = stab.reason;
  ev.stability_method = config_.stability ? stab.method : "";
  for (auto& o : ev.scenarios) o.metrics["spectral_radius"] = ev.spectral_radius;

  // Aggregation: the mean of every metric, plus each objective/constraint aggregate.
  auto column = [&](const std::string& metric) {
    std::vector<double> v;
    for (const auto& o : ev.scenarios) v.push_back(o.metrics.at(metric));
    if (v.empty()) v.push_back(metric == "spectral_radius" ? ev.spectral_radius : 0.0);
    return v;
  };
  for (const auto& name : metric_names(base.model))
    ev.aggregated[name] = aggregate(column(name), Aggregate::kMean, 0);
  ev.cost = 0.0;
  for (const auto& t : config_.objective) {
    const double a = aggregate(column(t.metric), t.how, t.alpha);
    ev.aggregated[std::string(to_string(t.how)) + "(" + t.metric + ")"] = a;
    ev.cost += t.weight * a;
  }
  bool finite = std::isfinite(ev.cost);
  for (const auto& o : config_.objectives) {
    double v = 0.0;
    for (const auto& t : o.terms) {
      const double a = aggregate(column(t.metric), t.how, t.alpha);
      ev.aggregated[std::string(to_string(t.how)) + "(" + t.metric + ")"] = a;
      v += t.weight * a;
    }
    ev.objectives.push_back(v);
    finite = finite && std::isfinite(v);
  }
  for (const auto& c : config_.constraints) {
    const double a = aggregate(column(c.metric), c.how, c.alpha);
    ev.aggregated[std::string(to_string(c.how)) + "(" + c.metric + ")"] = a;
    ev.constraints.push_back(c.has_max ? a - c.max : c.min - a);
  }
  if (!finite) {
    ev.ok = false;
    ev.failure = "non-finite cost";
    ev.cost = config_.failure_cost;
    ev.objectives.assign(config_.objectives.size(), config_.failure_cost);
    ev.constraints.assign(config_.constraints.size(), config_.failure_cost);
  }
}

Evaluation Evaluator::evaluate_impl(const std::vector<double>& unit, bool parallel,
                                    const std::function<void()>* on_trial) const {
  if (config_.farm) return evaluate_on_farm({unit}).front();
  const auto t0 = std::chrono::steady_clock::now();
  Evaluation ev;
  scene::Scene base;
  if (!bind(unit, ev, base)) {
    ev.wall_time = seconds_since(t0);
    return ev;
  }
  ev.binding_time = seconds_since(t0);
  // The scenario runs and the stability analysis, in parallel.
  const long n = static_cast<long>(config_.scenarios.scenarios.size());
  std::vector<JobOutcome> jobs(static_cast<size_t>(n) + 1);
  auto job = [&](long i) {
    jobs[static_cast<size_t>(i)] = run_job(base, i);
    if (on_trial && i > 0) (*on_trial)();  // job 0 is the stability analysis, not a trial
  };
  if (parallel && pool_->threads() > 1) {
    // Longest first (job_schedule.hpp); each job writes its own slot.
    const std::vector<long> order = schedule_->order(n + 1);
    std::vector<double> seconds(static_cast<size_t>(n) + 1, 0.0);
    pool_->parallel_for(n + 1, [&](long k) {
      const long i = order[static_cast<size_t>(k)];
      const auto start = std::chrono::steady_clock::now();
      job(i);
      seconds[static_cast<size_t>(i)] = seconds_since(start);
    });
    schedule_->record(std::move(seconds));
  } else {
    for (long i = 0; i <= n; ++i) job(i);
  }
  finish(ev, base, jobs);
  ev.wall_time = seconds_since(t0);
  return ev;
}

nlohmann::json Evaluator::compute_job(const std::vector<double>& job) const {
  if (job.empty()) throw std::runtime_error("a job without its index");
  const std::vector<double> unit(job.begin() + 1, job.end());
  Evaluation ev;
  scene::Scene base;
  if (!bind(unit, ev, base)) throw std::runtime_error("a job whose parameters bind to no scene");
  return job_outcome_to_wire(run_job(base, static_cast<long>(job.front())));
}

std::vector<Evaluation> Evaluator::evaluate_on_farm(
    const std::vector<std::vector<double>>& xs) const {
  const auto t0 = std::chrono::steady_clock::now();
  const long n = static_cast<long>(config_.scenarios.scenarios.size());
  std::vector<Evaluation> evs(xs.size());
  std::vector<scene::Scene> bases(xs.size());
  std::vector<std::vector<double>> jobs;
  std::vector<size_t> owner;  // the point each job belongs to
  for (size_t p = 0; p < xs.size(); ++p) {
    if (!bind(xs[p], evs[p], bases[p])) continue;
    for (long i = 0; i <= n; ++i) {
      std::vector<double> job{static_cast<double>(i)};
      job.insert(job.end(), xs[p].begin(), xs[p].end());
      jobs.push_back(std::move(job));
      owner.push_back(p);
    }
  }
  const double binding = seconds_since(t0);
  const std::vector<nlohmann::json> answers = config_.farm->run(farm_id_, *this, jobs);
  std::vector<std::vector<JobOutcome>> outcomes(xs.size());
  for (size_t j = 0; j < jobs.size(); ++j)
    outcomes[owner[j]].push_back(job_outcome_from_wire(answers[j]));
  for (size_t p = 0; p < xs.size(); ++p) {
    if (evs[p].ok) finish(evs[p], bases[p], outcomes[p]);
    evs[p].binding_time = binding;
    evs[p].wall_time = seconds_since(t0);
  }
  return evs;
}

ProblemEvaluation Evaluator::to_problem(const Evaluation& e) {
  ProblemEvaluation p;
  p.ok = e.ok;
  p.cost = e.cost;
  p.constraints = e.constraints;
  p.failure = e.failure;
  return p;
}

ProblemEvaluation Evaluator::evaluate(const std::vector<double>& x) const {
  return to_problem(evaluate_full(x));
}

std::vector<Evaluation> Evaluator::evaluate_full_batch(
    const std::vector<std::vector<double>>& xs) const {
  if (config_.farm) return evaluate_on_farm(xs);
  if (static_cast<int>(xs.size()) < pool_->threads()) {
    std::vector<Evaluation> out;
    for (const auto& x : xs) out.push_back(evaluate_full(x));
    return out;
  }
  std::vector<Evaluation> out(xs.size());
  pool_->parallel_for(static_cast<long>(xs.size()), [&](long i) {
    out[static_cast<size_t>(i)] = evaluate_impl(xs[static_cast<size_t>(i)], false);
  });
  return out;
}

std::vector<ProblemEvaluation> Evaluator::evaluate_batch(
    const std::vector<std::vector<double>>& xs) const {
  if (config_.farm) {
    std::vector<ProblemEvaluation> out;
    for (const auto& e : evaluate_on_farm(xs)) out.push_back(to_problem(e));
    return out;
  }
  if (static_cast<int>(xs.size()) < pool_->threads()) {
    // Fewer points than threads: parallel over each point's scenarios instead.
    std::vector<ProblemEvaluation> out;
    for (const auto& x : xs) out.push_back(to_problem(evaluate_full(x)));
    return out;
  }
  // Parallel over points, each point's scenarios serial: same numbers either way.
  std::vector<ProblemEvaluation> out(xs.size());
  pool_->parallel_for(static_cast<long>(xs.size()), [&](long i) {
    out[static_cast<size_t>(i)] = to_problem(evaluate_impl(xs[static_cast<size_t>(i)], false));
  });
  return out;
}

}  // namespace pronk::optimize
