// `pronk bench`'s robustness of the fidelity ladder: each rung on the same seeded disturbance
// trials of the shipped map_seed_duty study at a few duty cycles, its bisected boundary, and
// its disagreements with the pulse rung, trial by trial.
#include <string>
#include <vector>

#include "app/bench/suite.hpp"
#include "io/load/scene_loader.hpp"
#include "optimize/map/map_engine.hpp"
#include "optimize/map/map_study.hpp"
#include "optimize/progress.hpp"

namespace pronk::app::bench {

namespace {

/// The ladder's robustness study for one model: the shipped map_seed_duty study (scene,
/// seed, disturbances, 12 s trials, "stabilized" criterion) at its row 0 (no extra roll: row
/// seeding keys the trials by row, so trial t here is trial t of that row), on a 1-D duty
/// axis, with the first `trials` trials and the full model's settings of the ladder.
optimize::map::MapStudy robustness_study(const BenchConfig& c, const std::string& rung,
                                         const std::vector<double>& duties, long trials) {
  // The rigid rung is the full model with the rigid body.
  const bool rigid = rung == "rigid";
  const std::string model = rigid ? "pseudo_rigid" : rung;
  using nlohmann::json;
  const std::string file = c.studies_dir + "/map_seed_duty.json";
  json doc = io::read_json_file(file);
  doc["name"] = "fidelity_robustness_" + rung;
  doc["models"] = json::array({model});
  doc["axes"] = json::array({json{{"kind", "duty_cycle"}, {"values", duties}}});
  doc["trials"]["count"] = trials;
  doc["stability"] = true;
  // Three bisection probes from a 0.1 bracket (0.1 -> 0.05 -> 0.025 -> 0.0125 wide); the map's
  // default, spacing / 8, rounds to just below 0.0125 and would take a fourth.
  doc["boundary"] = {{"resolution", 0.015}};
  doc["scene_overrides"].push_back(std::string("/pseudo_rigid=") + kFullModelSettings);
  if (rigid) doc["scene_overrides"].push_back("/pseudo_rigid/body=\"rigid\"");
  return optimize::map::parse_map_study(doc, file, c.studies_dir);
}

RungRobustness robustness_rung(const optimize::map::MapStudy& st, const std::string& rung,
                               optimize::ProgressStyle style) {
  namespace m = optimize::map;
  RungRobustness r;
  r.model = rung;
  const double c0 = thread_cpu();
  std::vector<m::CellResult> cells;
  optimize::Progress progress(style, "bench: robustness, " + rung + " rung: cell", st.cells());
  for (long i = 0; i < st.cells(); ++i) {
    cells.push_back(m::compute_cell(st, i));
    progress.update(i + 1);
  }
  progress.finish();
  const std::vector<m::CellSummary> sums = m::summarize(st, cells);
  const m::BoundaryResult b = m::bisect_row(st, m::initial_bracket(st, sums, 0));
  r.cpu_s = thread_cpu() - c0;
  r.boundary_status = b.status;
  r.boundary = b.boundary;
  r.bad = b.bad;
  r.first_good = b.status == "none_good" ? 0.0 : b.first_good;
  r.probes = b.probes;
  const long n = st.trials.count;
  for (size_t i = 0; i < cells.size(); ++i) {
    RobustnessCell cell;
    cell.duty = sums[i].value0;
    cell.trials = n;
    for (const m::TrialOutcome& t : cells[i].trials[0]) {
      cell.verdicts.push_back(t.stabilized);
      cell.stabilized += t.stabilized ? 1 : 0;
      cell.fell += t.status != "completed" ? 1 : 0;
    }
    cell.fraction = static_cast<double>(cell.stabilized) / static_cast<double>(n);
    cell.mean_duty = sums[i].mean_duty;
    cell.spectral_radius = sums[i].spectral_radius;
    r.cells.push_back(std::move(cell));
  }
  return r;
}

}  // namespace

LadderRobustness ladder_robustness(const BenchConfig& c) {
  // Duties across the seed controller's limit (~29 % in map_seed_duty); 8 trials per cell:
  // a 12 s trial of the full model costs ~1.5 s, so its rung (32 trials, 3 bisection probes
  // of up to 8 trials, 4 fitted radii) stays near 2 min; the reduced rungs cost milliseconds.
  const std::vector<double> duties = {0.1, 0.2, 0.3, 0.4};
  const long trials = 8;
  LadderRobustness out;
  out.duties = duties;
  for (const char* model : {"impulse", "pulse", "rigid", "pseudo_rigid"}) {
    const optimize::map::MapStudy st = robustness_study(c, model, duties, trials);
    out.study = st.file + " (row 0: no extra roll)";
    out.trials = st.trials.count;
    out.seed = st.trials.seed;
    out.trial_duration = st.trial_set.duration;
    out.resolution = st.resolution;
    if (c.quick && scene::is_full_model(st.primary_model())) {
      RungRobustness r;
      r.model = model;
      r.available = false;
      r.note = "not run with --quick: the full model costs ~1.5 s per 12 s trial";
      out.rungs.push_back(r);
      continue;
    }
    out.rungs.push_back(robustness_rung(st, model, c.progress));
  }
  // Disagreements with the pulse rung, trial by trial (the seed's criterion).
  const RungRobustness* pulse = nullptr;
  for (const auto& r : out.rungs)
    if (r.model == "pulse") pulse = &r;
  for (auto& r : out.rungs) {
    if (!r.available || pulse == nullptr) continue;
    for (size_t i = 0; i < r.cells.size(); ++i) {
      RobustnessCell& cell = r.cells[i];
      const auto& ref = pulse->cells[i].verdicts;
      for (size_t t = 0; t < cell.verdicts.size() && t < ref.size(); ++t) {
        cell.only_this += cell.verdicts[t] && !ref[t] ? 1 : 0;
        cell.only_pulse += ref[t] && !cell.verdicts[t] ? 1 : 0;
      }
      r.disagreements_vs_pulse += cell.only_this + cell.only_pulse;
    }
  }
  return out;
}

}  // namespace pronk::app::bench
