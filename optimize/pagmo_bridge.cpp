#include "optimize/pagmo_bridge.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace pronk::optimize::detail {

PagmoBridge::PagmoBridge(EvaluationTracker& tracker, const Problem& problem, double penalty_weight)
    : tracker_(tracker),
      penalty_weight_(penalty_weight),
      lower_(problem.lower_bounds()),
      upper_(problem.upper_bounds()) {}

PagmoBridge::Key PagmoBridge::key_of(const std::vector<double>& x) {
  Key k(x.size());
  std::memcpy(k.data(), x.data(), x.size() * sizeof(double));
  return k;
}

double PagmoBridge::fitness_value(const ProblemEvaluation& e) const {
  double v = tracker_.optimizer_cost(e);
  if (penalty_weight_ > 0.0) {
    for (double g : e.constraints) v += penalty_weight_ * std::max(g, 0.0) * std::max(g, 0.0);
  }
  return v;
}

bool PagmoBridge::evaluate(const std::vector<std::vector<double>>& xs,
                           std::vector<double>* values) {
  std::vector<ProblemEvaluation> out;
  if (!tracker_.evaluate(xs, std::vector<const char*>(xs.size(), "objective"), &out)) return false;
  values->resize(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    (*values)[i] = fitness_value(out[i]);
    answers_[key_of(xs[i])] = (*values)[i];
  }
  return true;
}

double PagmoBridge::fitness(const std::vector<double>& x) {
  Key k = key_of(x);
  if (const auto it = answers_.find(k); it != answers_.end()) {
    used_.insert(std::move(k));
    return it->second;
  }
  if (dry_run_) {
    if (std::find(pending_.begin(), pending_.end(), x) == pending_.end()) pending_.push_back(x);
    return std::numeric_limits<double>::infinity();
  }
  std::vector<double> v;
  if (!evaluate({x}, &v)) throw PagmoStop{};
  used_.insert(std::move(k));
  return v[0];
}

void PagmoBridge::begin_generation() {
  answers_.clear();
  used_.clear();
  pending_.clear();
}

void PagmoBridge::begin_dry_run() {
  dry_run_ = true;
  used_.clear();
  pending_.clear();
}

void PagmoBridge::end_dry_run() { dry_run_ = false; }

long PagmoBridge::unused_answers() const {
  return static_cast<long>(answers_.size()) - static_cast<long>(used_.size());
}

pagmo::vector_double PagmoProblem::fitness(const pagmo::vector_double& x) const {
  return {bridge_->fitness(x)};
}

std::pair<pagmo::vector_double, pagmo::vector_double> PagmoProblem::get_bounds() const {
  if (bridge_ == nullptr) return {{0.0}, {1.0}};  // a default-constructed UDP (never evaluated)
  return {bridge_->lower(), bridge_->upper()};
}

pagmo::vector_double PagmoBatchEvaluator::operator()(const pagmo::problem& p,
                                                     const pagmo::vector_double& dvs) const {
  const std::size_t n = p.get_nx();
  std::vector<std::vector<double>> xs;
  for (std::size_t i = 0; n > 0 && i + n <= dvs.size(); i += n)
    xs.emplace_back(dvs.begin() + static_cast<long>(i), dvs.begin() + static_cast<long>(i + n));
  std::vector<double> values;
  bridge_->begin_generation();  // one call per generation: keep only this one's answers
  if (!bridge_->evaluate(xs, &values)) throw PagmoStop{};
  return values;
}

}  // namespace pronk::optimize::detail
