#include "optimize/pareto/moo_driver.hpp"

#include <pagmo/algorithm.hpp>
#include <pagmo/bfe.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "optimize/pareto/moo_algorithm.hpp"

namespace pronk::optimize::pareto {

namespace {

bool same_bits(const Point& a, const Point& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// Every evaluation of a run, in order: answered from the record while it lasts, then by the
/// batch function, one call per request.
class Evaluator {
 public:
  Evaluator(const BatchFunction& f, std::size_t objectives,
            const std::vector<MooEvaluation>& recorded)
      : f_(f), objectives_(objectives), recorded_(recorded) {}

  std::vector<Objectives> evaluate(const std::vector<Point>& xs) {
    std::vector<Objectives> out;
    std::size_t i = 0;
    for (; i < xs.size() && log.size() < recorded_.size(); ++i) {
      const MooEvaluation& r = recorded_[log.size()];
      if (!same_bits(r.x, xs[i]))
        throw std::invalid_argument("resume: recorded evaluation " + std::to_string(log.size()) +
                                    " is not the point the run asks for (other options, seed, "
                                    "bounds or record?)");
      check(r.f, "recorded evaluation " + std::to_string(log.size()));
      out.push_back(r.f);
      log.push_back(r);
      ++recorded_answers;
    }
    if (i == xs.size()) return out;
    const std::vector<Point> rest(xs.begin() + static_cast<long>(i), xs.end());
    std::vector<std::vector<double>> ys = f_(rest);
    ++batch_calls;
    if (ys.size() != rest.size())
      throw std::invalid_argument("batch function: " + std::to_string(ys.size()) + " answers for " +
                                  std::to_string(rest.size()) + " points");
    for (std::size_t k = 0; k < rest.size(); ++k) {
      check(ys[k], "batch function: point " + std::to_string(k) + " of the batch");
      log.push_back({rest[k], ys[k]});
      out.push_back(std::move(ys[k]));
    }
    return out;
  }

  std::vector<MooEvaluation> log;
  long batch_calls = 0;
  long recorded_answers = 0;

 private:
  void check(const Objectives& f, const std::string& where) const {
    if (f.size() != objectives_)
      throw std::invalid_argument(where + ": " + std::to_string(f.size()) +
                                  " objectives, expected " + std::to_string(objectives_));
    for (double v : f)
      if (!std::isfinite(v))
        throw std::invalid_argument(where +
                                    ": a non-finite objective (report a failed "
                                    "evaluation as a large finite penalty)");
  }

  const BatchFunction& f_;
  std::size_t objectives_;
  const std::vector<MooEvaluation>& recorded_;
};

/// pagmo's user-defined problem: the box, `objectives` objectives, each point evaluated
/// alone through the Evaluator (moead's path). Default-constructible as pagmo requires.
class MooProblem {
 public:
  MooProblem() = default;
  MooProblem(Evaluator* e, std::vector<double> lower, std::vector<double> upper,
             std::size_t objectives)
      : e_(e), lower_(std::move(lower)), upper_(std::move(upper)), objectives_(objectives) {}
  pagmo::vector_double fitness(const pagmo::vector_double& x) const { return e_->evaluate({x})[0]; }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {lower_, upper_};
  }
  pagmo::vector_double::size_type get_nobj() const { return objectives_; }
  std::string get_name() const { return "pronk multi-objective problem"; }

 private:
  Evaluator* e_ = nullptr;
  std::vector<double> lower_ = {0.0}, upper_ = {1.0};
  std::size_t objectives_ = 2;
};

/// pagmo's user-defined batch evaluator: the decision vectors pagmo hands over (the first
/// population, a generation of nsga2 or nspso) as one Evaluator request.
class MooBatchEvaluator {
 public:
  MooBatchEvaluator() = default;
  explicit MooBatchEvaluator(Evaluator* e) : e_(e) {}
  pagmo::vector_double operator()(const pagmo::problem& p, const pagmo::vector_double& dvs) const {
    const std::size_t n = p.get_nx();
    std::vector<Point> xs;
    for (std::size_t i = 0; i + n <= dvs.size(); i += n)
      xs.emplace_back(dvs.begin() + static_cast<long>(i), dvs.begin() + static_cast<long>(i + n));
    pagmo::vector_double flat;
    for (const Objectives& f : e_->evaluate(xs)) flat.insert(flat.end(), f.begin(), f.end());
    return flat;
  }
  std::string get_name() const { return "pronk multi-objective batch evaluator"; }

 private:
  Evaluator* e_ = nullptr;
};

void check_bounds(const std::vector<double>& lower, const std::vector<double>& upper) {
  if (lower.empty() || lower.size() != upper.size())
    throw std::invalid_argument("bounds: " + std::to_string(lower.size()) + " lower and " +
                                std::to_string(upper.size()) +
                                " upper: expected as many, at least one");
  for (std::size_t j = 0; j < lower.size(); ++j)
    if (!std::isfinite(lower[j]) || !std::isfinite(upper[j]) || !(lower[j] < upper[j]))
      throw std::invalid_argument("bounds: variable " + std::to_string(j) +
                                  ": expected finite bounds with lower < upper");
}

/// Two 32-bit pagmo seeds (first population, algorithm) from the run's 64-bit seed
/// (std::seed_seq: specified by the standard, the same everywhere).
std::pair<unsigned, unsigned> pagmo_seeds(std::uint64_t seed) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)};
  std::uint32_t out[2];
  seq.generate(out, out + 2);
  return {out[0], out[1]};
}

/// Appends the state after a generation to the result: population, the front of every
/// evaluation so far, its hypervolume.
void record(const pagmo::population& pop, long index, const Evaluator& e,
            std::vector<Objectives>* all_f, std::vector<std::size_t>* front, MooResult* r) {
  const std::size_t old = all_f->size();
  for (std::size_t i = old; i < e.log.size(); ++i) all_f->push_back(e.log[i].f);
  extend_front(*all_f, old, front);
  MooGeneration g;
  g.index = index;
  g.evaluations = static_cast<long>(e.log.size());
  g.x = pop.get_x();
  g.f = pop.get_f();
  g.front = *front;
  std::vector<Objectives> points;
  points.reserve(front->size());
  for (std::size_t k : *front) points.push_back((*all_f)[k]);
  g.hypervolume = hypervolume(points, r->reference);
  r->hypervolumes.push_back(g.hypervolume);
  r->generations.push_back(std::move(g));
}

/// The first population: pagmo's (uniform from the seed, one batch), or with
/// `initial_points` first, then uniform draws from the same seed, evaluated as one batch.
pagmo::population first_population(const pagmo::problem& problem, const pagmo::bfe& batch,
                                   Evaluator& e, const MooOptions& options, unsigned seed) {
  const auto size = static_cast<pagmo::pop_size_t>(options.population);
  if (options.initial_points.empty()) return pagmo::population{problem, batch, size, seed};
  pagmo::population pop{problem, 0u, seed};
  std::vector<Point> xs = options.initial_points;
  while (xs.size() < size) xs.push_back(pop.random_decision_vector());
  const std::vector<Objectives> fs = e.evaluate(xs);
  for (std::size_t i = 0; i < xs.size(); ++i) pop.push_back(xs[i], fs[i]);
  return pop;
}

void check_initial_points(const MooOptions& options, const std::vector<double>& lower,
                          const std::vector<double>& upper) {
  if (static_cast<long>(options.initial_points.size()) > options.population)
    throw std::invalid_argument("initial points: " + std::to_string(options.initial_points.size()) +
                                ": expected at most the population, " +
                                std::to_string(options.population));
  for (std::size_t k = 0; k < options.initial_points.size(); ++k) {
    const Point& x = options.initial_points[k];
    bool inside = x.size() == lower.size();
    for (std::size_t j = 0; inside && j < x.size(); ++j)
      inside = x[j] >= lower[j] && x[j] <= upper[j];
    if (!inside)
      throw std::invalid_argument("initial point " + std::to_string(k) +
                                  ": expected a point of the box's dimension inside it");
  }
}

}  // namespace

MooResult run(const BatchFunction& f, const std::vector<double>& lower,
              const std::vector<double>& upper, long objectives, const MooOptions& options,
              const MooObserver& observer, const std::vector<MooEvaluation>& recorded) {
  const std::vector<std::string> errors = options.validate(objectives);
  if (!errors.empty()) {
    std::string text;
    for (const auto& e : errors) text += (text.empty() ? "" : "; ") + e;
    throw std::invalid_argument("invalid options: " + text);
  }
  check_bounds(lower, upper);
  check_initial_points(options, lower, upper);
  const auto nobj = static_cast<std::size_t>(objectives);
  const auto [population_seed, algorithm_seed] = pagmo_seeds(options.seed);
  Evaluator e(f, nobj, recorded);
  const pagmo::problem problem{MooProblem(&e, lower, upper, nobj)};
  const pagmo::bfe batch{MooBatchEvaluator(&e)};
  pagmo::population pop = first_population(problem, batch, e, options, population_seed);

  MooResult r;
  r.reference = options.reference.empty() ? reference_point(pop.get_f()) : options.reference;
  std::vector<Objectives> all_f;
  std::vector<std::size_t> front;
  record(pop, 0, e, &all_f, &front, &r);
  if (observer) observer(r.generations.back(), e.log);
  pagmo::algorithm algo = detail::make_moo_algorithm(
      options, algorithm_seed, detail::moo_native_batch(options) ? &batch : nullptr);
  for (long g = 1; g <= options.generations; ++g) {
    pop = algo.evolve(pop);
    record(pop, g, e, &all_f, &front, &r);
    if (observer) observer(r.generations.back(), e.log);
  }

  for (std::size_t k : front) {
    r.front_x.push_back(e.log[k].x);
    r.front_f.push_back(e.log[k].f);
  }
  r.knee = knee(r.front_f);
  r.batch_calls = e.batch_calls;
  r.recorded_answers = e.recorded_answers;
  r.evaluations = std::move(e.log);
  return r;
}

}  // namespace pronk::optimize::pareto
