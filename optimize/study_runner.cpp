#include "optimize/study_runner.hpp"

#include <unistd.h>

#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

#include "io/build_info.hpp"
#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/figure_batch.hpp"
#include "io/write/run_output.hpp"
#include "io/write/simulation_output.hpp"
#include "optimize/journal.hpp"
#include "optimize/journal_check.hpp"
#include "optimize/output_lock.hpp"
#include "optimize/progress.hpp"
#include "optimize/reproduction_record.hpp"
#include "optimize/study_history.hpp"
#include "optimize/validation_run.hpp"
#include "sim/simulate.hpp"

namespace pronk::optimize {

std::string metric_rows(const MetricMap& a, const MetricMap& b, bool stability) {
  auto value = [](const MetricMap& m, const std::string& k) {
    const auto it = m.find(k);
    return it != m.end() ? it->second : 0.0;
  };
  std::ostringstream md;
  for (const auto& [k, v] : b) {
    if (k == "spectral_radius" && !stability) continue;
    if (k.size() > 6 && k.rfind("mean(", 0) == 0 && k.back() == ')') {
      const std::string m = k.substr(5, k.size() - 6);
      if (b.count(m) && value(b, m) == v && value(a, m) == value(a, k)) continue;
    }
    md << "| " << k << " | " << value(a, k) << " | " << v << " |\n";
  }
  return md.str();
}

using nlohmann::json;

namespace {

// The Problem the driver sees: replays the journal on --resume (same points in
// the same order give the recorded results without simulating), otherwise
// evaluates and keeps the full evaluation for the journal writer.
class StudyProblem final : public Problem {
 public:
  StudyProblem(const Evaluator& ev, std::vector<JournalRecord> replay)
      : ev_(ev), replay_(std::move(replay)) {}
  int dimension() const override { return ev_.dimension(); }
  int num_constraints() const override { return ev_.num_constraints(); }
  std::vector<double> lower_bounds() const override { return ev_.lower_bounds(); }
  std::vector<double> upper_bounds() const override { return ev_.upper_bounds(); }
  std::vector<double> initial_point() const override { return ev_.initial_point(); }
  std::vector<std::string> variable_names() const override { return ev_.variable_names(); }
  std::vector<std::string> constraint_names() const override { return ev_.constraint_names(); }

  ProblemEvaluation evaluate(const std::vector<double>& x) const override {
    ProblemEvaluation p;
    if (take_replay(x, &p)) return p;
    Evaluation e = ev_.evaluate_full(x);
    p = Evaluator::to_problem(e);
    keep(std::move(e));
    return p;
  }
  std::vector<ProblemEvaluation> evaluate_batch(
      const std::vector<std::vector<double>>& xs) const override {
    std::vector<ProblemEvaluation> out(xs.size());
    size_t i = 0;
    for (; i < xs.size() && take_replay(xs[i], &out[i]); ++i) {
    }
    std::vector<std::vector<double>> rest(xs.begin() + static_cast<long>(i), xs.end());
    std::vector<Evaluation> full = ev_.evaluate_full_batch(rest);
    for (size_t k = 0; k < full.size(); ++k) {
      out[i + k] = Evaluator::to_problem(full[k]);
      keep(std::move(full[k]));
    }
    return out;
  }
  /// The full evaluation of x made most recently (removed), if any.
  bool take(const std::vector<double>& x, Evaluation* e) const {
    std::lock_guard<std::mutex> lock(m_);
    auto it = cache_.find(x);
    if (it == cache_.end() || it->second.empty()) return false;
    *e = std::move(it->second.front());
    it->second.pop_front();
    if (it->second.empty()) cache_.erase(it);
    return true;
  }
  long replayed() const {
    std::lock_guard<std::mutex> lock(m_);
    return static_cast<long>(pos_);
  }
  /// Keeps a journaled evaluation when it is the first or the lowest-cost one so far: the
  /// study evaluates its starting and its tuned design once more in full at the end, and
  /// an evaluation is a pure function of x (the same numbers; two kept at most).
  void remember(const Evaluation& e) const {
    std::lock_guard<std::mutex> lock(m_);
    if (!first_) {
      first_ = e;
    } else if (e.ok && (!lowest_ || e.cost < lowest_->cost)) {
      lowest_ = e;
    }
  }
  /// The full evaluation of x, kept by remember() or made now.
  Evaluation evaluate_full(const std::vector<double>& x) const {
    {
      std::lock_guard<std::mutex> lock(m_);
      for (const auto* kept : {&first_, &lowest_}) {
        if (*kept && (*kept)->unit == x) return **kept;
      }
    }
    return ev_.evaluate_full(x);
  }

 private:
  bool take_replay(const std::vector<double>& x, ProblemEvaluation* p) const {
    std::lock_guard<std::mutex> lock(m_);
    if (pos_ >= replay_.size()) return false;
    if (replay_[pos_].x != x) {
      replay_.resize(pos_);  // the driver left the recorded path: evaluate from here on
      return false;
    }
    *p = replay_[pos_++].result;
    return true;
  }
  void keep(Evaluation e) const {
    std::lock_guard<std::mutex> lock(m_);
    cache_[e.unit].push_back(std::move(e));
  }
  const Evaluator& ev_;
  mutable std::vector<JournalRecord> replay_;
  mutable size_t pos_ = 0;
  mutable std::map<std::vector<double>, std::deque<Evaluation>> cache_;
  mutable std::optional<Evaluation> first_, lowest_;
  mutable std::mutex m_;
};

// Writes each new evaluation to timings.csv and the journal, tracks progress.
class JournalObserver final : public EvaluationObserver {
 public:
  JournalObserver(const StudyProblem& problem, JournalWriter& journal, TimingsFile& timings,
                  long recorded, std::vector<std::string> names, Progress& progress)
      : problem_(problem),
        journal_(journal),
        timings_(timings),
        recorded_(recorded),
        names_(std::move(names)),
        progress_(progress) {}
  void on_evaluation(long index, const std::vector<double>& x, const ProblemEvaluation& e,
                     const char* purpose) override {
    const bool feasible = e.ok && std::all_of(e.constraints.begin(), e.constraints.end(),
                                              [](double g) { return g <= 1e-8; });
    if (feasible && e.cost < best_) best_ = e.cost;
    if (index >= recorded_) {
      Evaluation full;
      const bool evaluated = problem_.take(x, &full);
      if (!evaluated) {
        full.unit = x;
        full.ok = e.ok;
        full.cost = e.cost;
        full.constraints = e.constraints;
        full.failure = e.failure;
      }
      timings_.write(index, full);  // first: a kill between the two leaves a spare line
      journal_.append(journal_record(index, purpose, full, names_));
      if (evaluated) problem_.remember(full);
    }
    progress_.update(index + 1, "best feasible cost " +
                                    (std::isfinite(best_) ? std::to_string(best_) : "(none yet)"));
  }

 private:
  const StudyProblem& problem_;
  JournalWriter& journal_;
  TimingsFile& timings_;
  long recorded_;
  std::vector<std::string> names_;
  Progress& progress_;
  double best_ = INFINITY;
};

json metrics_json(const Evaluation& e) {
  json m = json::object();
  for (const auto& [k, v] : e.aggregated) m[k] = v;
  return m;
}

std::string figure_history() {
  // Linear axis: costs may be negative (e.g. a "stabilized" term with weight -1).
  return "set terminal svg size 900,500 dynamic enhanced font 'Helvetica,11'\n"
         "set output 'history.svg'\nset datafile separator ','\nset grid\n"
         "set title 'Optimization history'\nset xlabel 'evaluation'\nset ylabel 'cost'\n"
         "plot 'history.csv' every ::1 u 1:($3==1 ? $4 : 1/0) w p pt 7 ps 0.4 t 'cost', "
         "'' every ::1 u 1:(strlen(strcol(6))>0 ? $6 : 1/0) w l lw 2 t 'best feasible'\n";
}

std::string figure_compare(const std::string& title) {
  // Position errors, height and every attitude angle: a design can fail on any of them.
  return "set terminal svg size 900,900 dynamic enhanced font 'Helvetica,11'\n"
         "set output 'compare.svg'\nset datafile separator ','\nset grid\n"
         "set multiplot layout 3,2 title '" +
         title +
         "' noenhanced\n"
         "set xlabel 'time [s]'\n"
         "set title 'Lateral position y'; set ylabel 'y [m]'\n"
         "plot 'initial/trajectory.csv' every ::1 u 1:3 w l t 'initial', "
         "'tuned/trajectory.csv' every ::1 u 1:3 w l t 'tuned'\n"
         "set title 'Roll'; set ylabel 'roll [deg]'\n"
         "plot 'initial/trajectory.csv' every ::1 u 1:8 w l t 'initial', "
         "'tuned/trajectory.csv' every ::1 u 1:8 w l t 'tuned'\n"
         "set title 'Height'; set ylabel 'z [m]'\n"
         "plot 'initial/trajectory.csv' every ::1 u 1:4 w l t 'initial', "
         "'tuned/trajectory.csv' every ::1 u 1:4 w l t 'tuned'\n"
         "set title 'x - x_d'; set ylabel 'error [m]'\n"
         "plot 'initial/trajectory.csv' every ::1 u 1:($2-$14) w l t 'initial', "
         "'tuned/trajectory.csv' every ::1 u 1:($2-$14) w l t 'tuned'\n"
         "set title 'Pitch'; set ylabel 'pitch [deg]'\n"
         "plot 'initial/trajectory.csv' every ::1 u 1:9 w l t 'initial', "
         "'tuned/trajectory.csv' every ::1 u 1:9 w l t 'tuned'\n"
         "set title 'Yaw'; set ylabel 'yaw [deg]'\n"
         "plot 'initial/trajectory.csv' every ::1 u 1:10 w l t 'initial', "
         "'tuned/trajectory.csv' every ::1 u 1:10 w l t 'tuned'\n"
         "unset multiplot\n";
}

// The optimization history and the initial design against the tuned one (rendered together).
void render_study_figures(const std::string& dir, const std::string& compare_title) {
  io::FigureBatch figures;
  figures.add(dir, "history", figure_history());
  figures.add(dir, "compare", figure_compare(compare_title));
  figures.finish();
}

// The tuned design on the validation starts, the nominal robot beside the perturbed ones.
std::string validation_comparison(const StudyOutcome& o, bool stability) {
  std::ostringstream md;
  md << "\nThe tuned design on the same " << o.validation_best.scenarios.size()
     << " validation starts, with the nominal robot and with the robot perturbed as the set "
        "draws it (the controller knows only the nominal numbers):\n\n| metric | nominal robot "
        "| perturbed robot |\n|---|---|---|\n";
  md << "| cost | " << o.validation_nominal.cost << " | " << o.validation_best.cost << " |\n";
  md << metric_rows(o.validation_nominal.aggregated, o.validation_best.aggregated, stability);
  return md.str();
}

std::string summary_markdown(const Study& st, const StudyOutcome& o) {
  std::ostringstream md;
  const auto& ev = st.evaluator;
  md << "# Study `" << st.name << "`\n\n";
  md << "Optimizer: " << o.result.library << " " << o.result.algorithm << " — status **"
     << to_string(o.result.status) << "** (" << o.result.message << "), " << o.result.evaluations
     << " evaluations (" << o.replayed << " replayed from the journal), "
     << o.result.failed_evaluations << " failed, wall time " << o.wall_time << " s.\n\n";
  if (o.result.constraints_as_penalty) {
    md << "The algorithm does not support constraints: they were added to the cost as a "
          "penalty.\n\n";
  }
  md << "| parameter | initial | tuned | bounds |\n|---|---|---|---|\n";
  for (size_t i = 0; i < ev.parameters.size(); ++i) {
    md << "| " << ev.parameters[i].name << " | " << o.initial.values[i] << " | " << o.best.values[i]
       << " | [" << ev.parameters[i].lower << ", " << ev.parameters[i].upper << "]"
       << (ev.parameters[i].log_scale ? " log" : "") << " |\n";
  }
  md << "\n| metric (over " << ev.scenarios.scenarios.size()
     << " scenarios) | initial | tuned |\n|---|---|---|\n";
  md << "| cost | " << o.initial.cost << " | " << o.best.cost << " |\n";
  md << metric_rows(o.initial.aggregated, o.best.aggregated, ev.stability);
  md << "\nConstraints (g <= 0 is feasible):\n\n";
  for (size_t c = 0; c < ev.constraints.size(); ++c) {
    md << "- " << ev.constraints[c].label() << ": initial g = " << o.initial.constraints[c]
       << ", tuned g = " << o.best.constraints[c] << "\n";
  }
  if (o.validated) {
    md << "\nValidation on " << st.validation->scenarios.size()
       << " held-out scenarios (not seen by the optimizer):\n\n| metric | initial | tuned "
          "|\n|---|---|---|\n";
    md << metric_rows(o.validation_initial.aggregated, o.validation_best.aggregated, ev.stability);
    if (o.validation_compared) md << validation_comparison(o, ev.stability);
  }
  md << "\nFiles: `design.json` (reproduce with `pronk reproduce " << o.out_dir
     << "/design.json`), `history.csv`, `journal.jsonl`, `history.svg`, `compare.svg`, "
        "`initial/` and `tuned/` (first scenario, simulated).\n";
  return md.str();
}

}  // namespace

// Simulates a design on the first scenario and writes its outputs into dir.
void write_design_run(const std::string& dir, const Evaluator& ev, const std::vector<double>& x) {
  const scene::Scene base = ev.scene_at(x);
  const auto& set = ev.config().scenarios;
  const scene::Scene s = apply_scenario(base, set.scenarios.front(), set);
  const RunResult r = simulate(s);
  io::write_simulation_outputs(dir, s, r, reduced::compute_metrics(s, r.run));
}

json journal_header(const Study& st, const Evaluator& ev) {
  return {{"type", "header"},
          {"study", st.name},
          {"study_hash", st.hash},
          {"parameters", ev.variable_names()},
          {"constraints", ev.constraint_names()},
          {"optimizer", st.optimizer.library + ":" + st.optimizer.algorithm},
          {"seed", st.optimizer.seed}};
}

// The journal to resume, checked against the study (its hash, its last record, and with
// options.verify its records re-evaluated: *verified of them); nothing when there is none
// (or only a torn header). An existing journal without --resume is bad input.
JournalContents resumable_journal(const std::string& path, const Study& st, const Evaluator& ev,
                                  const StudyRunOptions& opt, long* verified) {
  JournalContents previous = read_journal(path);
  if (previous.header.is_null()) return {};
  if (!opt.resume) {
    throw io::InputError(path, "",
                         "no journal (pass --resume to continue it, or choose another --out)",
                         "the journal of an earlier run");
  }
  if (previous.header.value("study_hash", "") != st.hash) {
    throw io::InputError(path, "/study_hash", "the journal of this study (hash " + st.hash + ")",
                         "hash " + previous.header.value("study_hash", std::string("?")));
  }
  check_last_record(previous, ev, path);
  if (opt.verify >= 0) *verified = verify_records(previous, ev, opt.verify, opt.verify_seed, path);
  return previous;
}

std::string compiler_id() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "gcc " __VERSION__;
#else
  return "unknown";
#endif
}

Evaluator validation_evaluator(const Study& st, int threads, JobFarm* farm) {
  EvaluatorConfig cfg = st.evaluator;
  cfg.scenarios = *st.validation;
  cfg.threads = threads;
  cfg.farm = farm;
  return Evaluator(cfg);
}

json design_document(const Study& st, const StudyOutcome& o, int threads) {
  json values = json::object();
  for (size_t i = 0; i < st.evaluator.parameters.size(); ++i) {
    values[st.evaluator.parameters[i].name] = o.best.values[i];
  }
  // The study with its scene inlined: reproducible from this file alone.
  json study = st.document;
  study["scene"] = st.evaluator.scene_doc;
  study.erase("scene_overrides");
  study.erase("output");
  const scene::Scene tuned =
      io::parse_scene(bind_parameters(st.evaluator.scene_doc, st.evaluator.parameters, o.best.unit),
                      st.evaluator.scene_file);
  json validation = nullptr;
  if (o.validated) {
    validation = {{"scenarios", st.validation->scenarios.size()},
                  {"initial_cost", o.validation_initial.cost},
                  {"cost", o.validation_best.cost},
                  {"initial_metrics", metrics_json(o.validation_initial)},
                  {"metrics", metrics_json(o.validation_best)},
                  {"trials", to_json(trial_decisions(o.validation_best))}};
  }
  return {{"type", "pronk_design"},
          {"study", st.name},
          {"study_hash", st.hash},
          {"study_document_hash", parse_study(study, st.file, ".").hash},
          {"version", pronk::version()},
          {"commit", pronk::git_commit()},
          {"compiler", compiler_id()},
          {"build_flags", pronk::build_flags()},
          {"seed", st.optimizer.seed},
          {"threads", threads},
          {"wall_time_s", o.wall_time},
          {"optimizer",
           {{"library", o.result.library},
            {"algorithm", o.result.algorithm},
            {"status", std::string(to_string(o.result.status))},
            {"message", o.result.message},
            {"evaluations", o.result.evaluations},
            {"failed_evaluations", o.result.failed_evaluations}}},
          {"parameters", values},
          {"unit", o.best.unit},
          {"cost", o.best.cost},
          {"constraints", o.best.constraints},
          {"feasible", o.result.best_feasible},
          {"metrics", metrics_json(o.best)},
          {"trials", to_json(trial_decisions(o.best))},
          {"reproduction", o.reproduction},
          {"model", std::string(scene::to_string(o.best.model))},
          {"stability",
           {{"method", o.best.stability_method},
            {"ok", o.best.stability_reason.empty()},
            {"reason", o.best.stability_reason}}},
          {"initial_metrics", metrics_json(o.initial)},
          {"initial_cost", o.initial.cost},
          {"validation", validation},
          {"scene", io::scene_to_json(tuned)},
          {"study_document", study}};
}

StudyOutcome run_study(const Study& st, const StudyRunOptions& opt) {
  if (st.moo) {  // optimize/moo_study.hpp runs these
    throw io::InputError(st.file, "/optimizer/algorithm",
                         "a single-objective optimizer here (a multi-objective study runs as a "
                         "study of its own: pronk optimize STUDY)",
                         "\"" + st.moo->algorithm + "\"");
  }
  const double t0 = monotonic_seconds();
  StudyOutcome o;
  o.out_dir = opt.out_dir.empty() ? st.output_dir : opt.out_dir;
  io::make_directories(o.out_dir);
  const OutputLock lock(o.out_dir, "pronk optimize");
  remove_stale_temporaries(o.out_dir, 1);  // initial/, tuned/
  const std::string journal_path = o.out_dir + "/journal.jsonl";

  EvaluatorConfig cfg = st.evaluator;
  cfg.threads = opt.threads;
  cfg.farm = opt.farm;
  const Evaluator evaluator(cfg);

  JournalContents previous = resumable_journal(journal_path, st, evaluator, opt, &o.verified);
  const long recorded = static_cast<long>(previous.records.size());
  TimingsFile timings(o.out_dir, recorded > 0 ? &previous : nullptr);
  JournalWriter journal(journal_path, journal_header(st, evaluator),
                        recorded > 0 ? prepare_for_append(journal_path, previous.end) : "");
  StudyProblem problem(evaluator, std::move(previous.records));
  Progress progress(opt.progress, st.name + ": evaluation", st.optimizer.max_evaluations, recorded);
  JournalObserver observer(problem, journal, timings, recorded, evaluator.variable_names(),
                           progress);

  OptimizerOptions oo = st.optimizer;
  oo.stop_flag = opt.stop_flag;
  o.result = run_optimizer(problem, oo, &observer);
  progress.finish();
  o.replayed = problem.replayed();

  // The starting and the tuned design, fully evaluated (deterministic: same numbers as recorded).
  o.initial = problem.evaluate_full(evaluator.initial_point());
  o.best =
      problem.evaluate_full(o.result.best_x.empty() ? evaluator.initial_point() : o.result.best_x);
  std::optional<Evaluator> val;
  if (st.validation) run_validation(st, opt, t0, o, val);
  o.wall_time = monotonic_seconds() - t0;
  // What another build needs to reproduce the design honestly: the perturbation run (timed
  // on its own: the study's wall time stays the optimization's and the validation's).
  o.reproduction = record_reproduction(evaluator, o.best, val ? &*val : nullptr,
                                       val ? &o.validation_best : nullptr);
  o.reproduction["wall_time_s"] = monotonic_seconds() - t0 - o.wall_time;

  write_history(o.out_dir, journal_path, evaluator);
  io::write_file_atomic(o.out_dir + "/design.json",
                        io::dump_checked(design_document(st, o, opt.threads)));
  io::write_file_atomic(o.out_dir + "/summary.md", summary_markdown(st, o));
  write_design_run(o.out_dir + "/initial", evaluator, o.initial.unit);
  write_design_run(o.out_dir + "/tuned", evaluator, o.best.unit);
  render_study_figures(o.out_dir, st.name + ": initial vs tuned (first scenario)");
  return o;
}

}  // namespace pronk::optimize
