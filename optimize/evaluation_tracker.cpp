#include "optimize/evaluation_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <utility>

namespace pronk::optimize::detail {

namespace {

/// Cached points kept by FiniteDifferences (libraries revisit only the last few).
constexpr std::size_t kCacheSize = 8;

bool same_bits(const std::vector<double>& a, const double* b) {
  return std::memcmp(a.data(), b, a.size() * sizeof(double)) == 0;
}

double max_violation(const ProblemEvaluation& e) {
  double v = 0.0;
  for (double g : e.constraints) v = std::max(v, g);
  return v;
}

}  // namespace

// ---------------------------------------------------------------------------
// EvaluationTracker

EvaluationTracker::EvaluationTracker(const Problem& problem, const OptimizerOptions& options,
                                     EvaluationObserver* observer)
    : problem_(problem),
      options_(options),
      observer_(observer),
      m_(problem.num_constraints()),
      start_(std::chrono::steady_clock::now()) {}

double EvaluationTracker::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool EvaluationTracker::should_stop() {
  if (stopped()) return true;
  if (options_.stop_flag != nullptr && options_.stop_flag->load()) {
    cause_ = StopCause::kStopFlag;
    cause_message_ = "stop requested";
    return true;
  }
  if (options_.max_time > 0.0 && elapsed() >= options_.max_time) {
    cause_ = StopCause::kMaxTime;
    cause_message_ = "time limit of " + std::to_string(options_.max_time) + " s reached";
    return true;
  }
  return false;
}

void EvaluationTracker::record_error(const std::string& why) {
  if (cause_ == StopCause::kError) {
    cause_message_ += "; " + why;
    return;
  }
  cause_ = StopCause::kError;
  cause_message_ = why;
}

bool EvaluationTracker::evaluate(const std::vector<std::vector<double>>& xs,
                                 const std::vector<const char*>& purposes,
                                 std::vector<ProblemEvaluation>* out) {
  out->clear();
  if (should_stop()) return false;
  if (evaluations_ + static_cast<long>(xs.size()) > options_.max_evaluations) {
    cause_ = StopCause::kMaxEvaluations;
    cause_message_ =
        "evaluation budget of " + std::to_string(options_.max_evaluations) + " reached";
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    *out = problem_.evaluate_batch(xs);
  } catch (const std::exception& e) {
    record_error(std::string("Problem::evaluate threw: ") + e.what());
  } catch (...) {
    record_error("Problem::evaluate threw a non-standard exception");
  }
  evaluation_time_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (stopped()) {
    out->clear();
    return false;
  }
  if (out->size() != xs.size()) {
    record_error("Problem::evaluate_batch returned " + std::to_string(out->size()) +
                 " results for " + std::to_string(xs.size()) + " points");
    out->clear();
    return false;
  }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    ProblemEvaluation& e = (*out)[i];
    // Defensive sanitising: a Problem must never return NaN/inf, but if it
    // does the value is clamped and the evaluation counts as failed.
    bool nonfinite = !std::isfinite(e.cost);
    if (nonfinite) e.cost = kLargeValue;
    if (static_cast<int>(e.constraints.size()) != m_) {
      e.constraints.resize(static_cast<std::size_t>(m_), kLargeValue);
      e.ok = false;
      e.failure += (e.failure.empty() ? "" : "; ") + std::string("wrong number of constraints");
    }
    for (double& g : e.constraints) {
      if (!std::isfinite(g)) {
        g = kLargeValue;
        nonfinite = true;
      }
    }
    if (nonfinite) {
      ++nonfinite_;
      e.ok = false;
      e.failure += (e.failure.empty() ? "" : "; ") + std::string("non-finite value (clamped)");
    }
    const long index = evaluations_++;
    const char* purpose = i < purposes.size() ? purposes[i] : "objective";
    if (std::strcmp(purpose, "gradient") == 0) ++gradient_;
    if (e.ok) {
      highest_ok_cost_ = any_ok_ ? std::max(highest_ok_cost_, e.cost) : e.cost;
      any_ok_ = true;
    } else {
      ++failed_;
      failed_points_.push_back(xs[i]);
    }
    consider_best(index, xs[i], e);
    if (observer_ != nullptr && cause_ != StopCause::kError) {
      try {
        observer_->on_evaluation(index, xs[i], e, purpose);
      } catch (const std::exception& ex) {
        record_error(std::string("evaluation observer threw: ") + ex.what());
      } catch (...) {
        record_error("evaluation observer threw a non-standard exception");
      }
    }
  }
  return true;
}

double EvaluationTracker::optimizer_cost(const ProblemEvaluation& e) const {
  if (e.ok || !any_ok_) return e.cost;
  // A clamped non-finite value carries no information: use the worst
  // successful cost rather than kLargeValue (which would wreck a model).
  if (e.cost == kLargeValue) return highest_ok_cost_;
  return std::max(e.cost, highest_ok_cost_);
}

bool EvaluationTracker::failed_point(const std::vector<double>& x) const {
  for (const auto& p : failed_points_) {
    if (p.size() == x.size() && same_bits(p, x.data())) return true;
  }
  return false;
}

void EvaluationTracker::consider_best(long index, const std::vector<double>& x,
                                      const ProblemEvaluation& e) {
  if (!e.ok) return;  // best_x never comes from a failed evaluation
  const double violation = max_violation(e);
  const bool feasible = violation <= options_.feasibility_tolerance;
  bool better = false;
  if (!have_best_) {
    better = true;
  } else if (feasible != best_feasible_) {
    better = feasible;
  } else if (feasible) {
    better = e.cost < best_.cost;
  } else {
    better = violation < best_violation_ || (violation == best_violation_ && e.cost < best_.cost);
  }
  if (!better) return;
  have_best_ = true;
  best_feasible_ = feasible;
  best_violation_ = violation;
  best_index_ = index;
  best_x_ = x;
  best_ = e;
}

void append_message(std::string* message, const std::string& part) {
  if (part.empty()) return;
  if (!message->empty()) *message += "; ";
  *message += part;
}

void EvaluationTracker::apply_stop_cause(OptimizerResult* r) const {
  switch (stop_cause()) {
    case StopCause::kNone:
      break;
    case StopCause::kMaxEvaluations:
      r->status = OptimizerStatus::kMaxEvaluations;
      break;
    case StopCause::kMaxTime:
      r->status = OptimizerStatus::kMaxTime;
      break;
    case StopCause::kStopFlag:
      r->status = OptimizerStatus::kStopped;
      break;
    case StopCause::kError:
      r->status = OptimizerStatus::kFailed;
      break;
  }
  append_message(&r->message, stop_message());
}

void EvaluationTracker::fail(OptimizerResult* r, const std::string& cause) {
  record_error(cause);
  r->status = OptimizerStatus::kFailed;
  append_message(&r->message, stop_message());
}

void EvaluationTracker::finish(OptimizerResult* r) const {
  fill(r);
  if (r->best_index < 0) {
    if (r->status == OptimizerStatus::kConverged) r->status = OptimizerStatus::kFailed;
    append_message(&r->message, "no evaluation succeeded");
  }
}

void EvaluationTracker::fill(OptimizerResult* r) const {
  r->evaluations = evaluations_;
  r->failed_evaluations = failed_;
  r->gradient_evaluations = gradient_;
  r->nonfinite_evaluations = nonfinite_;
  r->best_index = have_best_ ? best_index_ : -1;
  r->best_x = have_best_ ? best_x_ : std::vector<double>{};
  r->best_cost = have_best_ ? best_.cost : 0.0;
  r->best_constraints = have_best_ ? best_.constraints : std::vector<double>{};
  r->best_feasible = have_best_ && best_feasible_;
  r->evaluation_time = evaluation_time_;
  r->wall_time = elapsed();
}

// ---------------------------------------------------------------------------
// FiniteDifferences

FiniteDifferences::FiniteDifferences(EvaluationTracker& tracker, const Problem& problem,
                                     const OptimizerOptions& options, ValueFunction value)
    : tracker_(tracker),
      options_(options),
      value_(std::move(value)),
      n_(problem.dimension()),
      m_(problem.num_constraints()),
      lower_(problem.lower_bounds()),
      upper_(problem.upper_bounds()) {}

std::shared_ptr<PointRecord> FiniteDifferences::find(const double* x) {
  for (const auto& r : cache_) {
    if (same_bits(r->x, x)) return r;
  }
  return nullptr;
}

std::shared_ptr<PointRecord> FiniteDifferences::insert(const double* x, ProblemEvaluation e) {
  auto r = std::make_shared<PointRecord>();
  r->x.assign(x, x + n_);
  r->eval = std::move(e);
  cache_.push_front(r);
  if (cache_.size() > kCacheSize) cache_.pop_back();
  return r;
}

std::shared_ptr<const PointRecord> FiniteDifferences::point(const double* x) {
  if (auto r = find(x)) return r;
  std::vector<ProblemEvaluation> out;
  if (!tracker_.evaluate({std::vector<double>(x, x + n_)}, {"objective"}, &out)) return nullptr;
  return insert(x, std::move(out[0]));
}

FiniteDifferences::Stencil FiniteDifferences::plan_stencil(const std::vector<double>& x0,
                                                           bool with_center) const {
  Stencil st;
  st.plan.resize(static_cast<std::size_t>(n_));
  if (with_center) {
    st.batch.push_back(x0);
    st.purposes.push_back("objective");
  }
  auto add = [&](int j, double xj) {
    std::vector<double> p = x0;
    p[static_cast<std::size_t>(j)] = xj;
    st.batch.push_back(std::move(p));
    st.purposes.push_back("gradient");
    return static_cast<int>(st.batch.size()) - 1;
  };
  const bool central = options_.fd_scheme == "central";
  for (int j = 0; j < n_; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const double lo = lower_[ju], hi = upper_[ju], xj = x0[ju];
    if (!(hi > lo)) continue;  // fixed variable: derivative 0
    const double scale =
        (std::isfinite(lo) && std::isfinite(hi)) ? hi - lo : std::max(1.0, std::abs(xj));
    const double h = options_.fd_step * scale;
    if (central && xj - h >= lo && xj + h <= hi) {
      st.plan[ju].first = add(j, xj + h);
      st.plan[ju].d_first = (xj + h) - xj;
      st.plan[ju].second = add(j, xj - h);
      st.plan[ju].d_second = (xj - h) - xj;
      continue;
    }
    double xp = xj + h;
    if (xp > hi) xp = xj - h;
    if (xp < lo) xp = (hi - xj >= xj - lo) ? hi : lo;
    if (xp - xj == 0.0) continue;
    st.plan[ju].first = add(j, xp);
    st.plan[ju].d_first = xp - xj;
  }
  return st;
}

bool FiniteDifferences::evaluate_mirrors(const std::vector<double>& x0,
                                         const std::vector<StencilPlan>& plan,
                                         const std::vector<ProblemEvaluation>& out,
                                         std::vector<std::pair<int, double>>* mirror_of,
                                         std::vector<ProblemEvaluation>* mirror_out) {
  std::vector<std::vector<double>> mirror;
  for (int j = 0; j < n_; ++j) {
    const StencilPlan& p = plan[static_cast<std::size_t>(j)];
    if (p.first < 0 || p.second >= 0 || out[static_cast<std::size_t>(p.first)].ok) continue;
    const double xq = x0[static_cast<std::size_t>(j)] - p.d_first;
    if (xq < lower_[static_cast<std::size_t>(j)] || xq > upper_[static_cast<std::size_t>(j)])
      continue;
    std::vector<double> q = x0;
    q[static_cast<std::size_t>(j)] = xq;
    mirror.push_back(std::move(q));
    mirror_of->emplace_back(j, xq - x0[static_cast<std::size_t>(j)]);
  }
  if (mirror.empty()) return true;
  return tracker_.evaluate(mirror, std::vector<const char*>(mirror.size(), "gradient"), mirror_out);
}

void FiniteDifferences::difference(PointRecord* rec, const std::vector<StencilPlan>& plan,
                                   const std::vector<ProblemEvaluation>& out,
                                   const std::vector<std::pair<int, double>>& mirror_of,
                                   const std::vector<ProblemEvaluation>& mirror_out) const {
  const ProblemEvaluation& e0 = rec->eval;
  const double f0 = value_(e0);
  const auto mu = static_cast<std::size_t>(m_);
  rec->gradient.assign(static_cast<std::size_t>(n_), 0.0);
  rec->jacobian.assign(mu * static_cast<std::size_t>(n_), 0.0);
  rec->derivatives_ok = e0.ok;
  auto one_sided = [&](int j, const ProblemEvaluation& e, double d) {
    const auto ju = static_cast<std::size_t>(j);
    rec->gradient[ju] = (value_(e) - f0) / d;
    for (std::size_t i = 0; i < mu; ++i)
      rec->jacobian[i * static_cast<std::size_t>(n_) + ju] =
          (e.constraints[i] - e0.constraints[i]) / d;
  };
  std::size_t next_mirror = 0;
  for (int j = 0; j < n_; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const StencilPlan& p = plan[ju];
    if (p.first < 0) continue;
    const ProblemEvaluation& a = out[static_cast<std::size_t>(p.first)];
    if (p.second >= 0) {
      const ProblemEvaluation& b = out[static_cast<std::size_t>(p.second)];
      if (a.ok && b.ok) {
        const double d = p.d_first - p.d_second;
        rec->gradient[ju] = (value_(a) - value_(b)) / d;
        for (std::size_t i = 0; i < mu; ++i)
          rec->jacobian[i * static_cast<std::size_t>(n_) + ju] =
              (a.constraints[i] - b.constraints[i]) / d;
      } else if (a.ok || b.ok) {
        one_sided(j, a.ok ? a : b, a.ok ? p.d_first : p.d_second);
      } else {
        one_sided(j, a, p.d_first);
        rec->derivatives_ok = false;
      }
      continue;
    }
    if (a.ok) {
      one_sided(j, a, p.d_first);
    } else if (next_mirror < mirror_of.size() && mirror_of[next_mirror].first == j) {
      const ProblemEvaluation& q = mirror_out[next_mirror];
      one_sided(j, q.ok ? q : a, q.ok ? mirror_of[next_mirror].second : p.d_first);
      if (!q.ok) rec->derivatives_ok = false;
      ++next_mirror;
    } else {
      one_sided(j, a, p.d_first);
      rec->derivatives_ok = false;
    }
  }
}

std::shared_ptr<const PointRecord> FiniteDifferences::derivatives(const double* x) {
  std::shared_ptr<PointRecord> rec = find(x);
  if (rec && rec->has_derivatives) return rec;
  // Plan the stencil: per variable a forward (or backward, at the upper
  // bound) point, or a central pair.
  const std::vector<double> x0(x, x + n_);
  const Stencil st = plan_stencil(x0, !rec);
  std::vector<ProblemEvaluation> out;
  if (!tracker_.evaluate(st.batch, st.purposes, &out)) return nullptr;
  if (!rec) rec = insert(x, out[0]);
  // Replace failed one-sided points by their mirror image when it is inside
  // the bounds (one more batch); a central pair with one failure degrades to
  // the successful side.
  std::vector<std::pair<int, double>> mirror_of;  // (variable, offset)
  std::vector<ProblemEvaluation> mirror_out;
  if (!evaluate_mirrors(x0, st.plan, out, &mirror_of, &mirror_out)) return nullptr;
  difference(rec.get(), st.plan, out, mirror_of, mirror_out);
  rec->has_derivatives = true;
  return rec;
}

}  // namespace pronk::optimize::detail
