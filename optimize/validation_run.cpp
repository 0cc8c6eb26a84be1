#include "optimize/validation_run.hpp"

#include <cstdio>
#include <functional>
#include <string>

#include "optimize/scenario.hpp"
#include "optimize/shared_progress.hpp"
#include "sim/run/count_text.hpp"

namespace pronk::optimize {

void run_validation(const Study& st, const StudyRunOptions& opt, double t0, StudyOutcome& o,
                    std::optional<Evaluator>& val) {
  const double v0 = monotonic_seconds();
  const long n = static_cast<long>(st.validation->scenarios.size());
  const bool nominal = st.validation->compare_nominal && perturbs_robot(*st.validation);
  const long designs = nominal ? 3 : 2;
  progress_note(opt.progress, "  " + st.name + ": validating on " +
                                  run::count_text(n, "held-out trial") +
                                  (nominal ? " (initial, tuned and tuned on the nominal robot), "
                                           : " (initial and tuned design), ") +
                                  format_duration(v0 - t0) + " elapsed");
  SharedProgress progress(opt.progress, st.name + ": validation trial runs", designs * n);
  const std::function<void()> on_trial = [&progress] { progress.add(); };
  long evaluated = 0;
  auto evaluate = [&](const Evaluator& e, const std::vector<double>& unit) {
    Evaluation ev = e.evaluate_full(unit, on_trial);
    progress.reach(++evaluated * n);  // a farm's evaluation counts its trials only at its end
    return ev;
  };
  val.emplace(validation_evaluator(st, opt.threads, opt.farm));
  o.validated = true;
  o.validation_initial = evaluate(*val, o.initial.unit);
  o.validation_best = evaluate(*val, o.best.unit);
  if (nominal) {
    Study nominal_study = st;
    nominal_study.validation = with_nominal_robot(*st.validation);
    o.validation_compared = true;
    o.validation_nominal =
        evaluate(validation_evaluator(nominal_study, opt.threads, opt.farm), o.best.unit);
  }
  progress.finish();
  char stabilized[32];
  std::snprintf(stabilized, sizeof stabilized, "%.1f %%",
                100.0 * o.validation_best.aggregated["stabilized"]);
  progress_note(opt.progress, "  " + st.name + ": validated in " +
                                  format_duration(monotonic_seconds() - v0) +
                                  ", tuned design stabilized in " + stabilized + " of them");
}

}  // namespace pronk::optimize
