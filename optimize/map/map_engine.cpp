#include "optimize/map/map_engine.hpp"

#include <algorithm>
#include <cmath>

#include "io/load/input_error.hpp"
#include "io/load/scene_loader.hpp"
#include "sim/math/rotation.hpp"
#include "sim/reduced/metrics.hpp"
#include "sim/simulate.hpp"

namespace pronk::optimize::map {

using nlohmann::json;

namespace {
constexpr double kDeg = M_PI / 180.0;

bool is_scene_axis(const MapAxis& a) {
  return a.kind == AxisKind::kPointer || a.kind == AxisKind::kDutyCycle;
}

// Kick size and direction of the derived velocity-kick axes, if any.
void apply_derived(const MapStudy& st, const double* values, scene::Scene& s) {
  bool kick = false;
  double kick_size = 0.0, kick_dir = 90.0 * kDeg;
  for (size_t i = 0; i < st.axes.size(); ++i) {
    const MapAxis& a = st.axes[i];
    const double v = values[i];
    switch (a.kind) {
      case AxisKind::kPointer:
        break;
      case AxisKind::kDutyCycle:
        apply_duty(s, v);
        break;
      case AxisKind::kTilt:
        s.initial.attitude =
            (s.initial.attitude * math::Quat(Eigen::AngleAxisd(v * kDeg, a.tilt_axis)))
                .normalized();
        break;
      case AxisKind::kLateralOffset:
        s.initial.position.y() += v;
        break;
      case AxisKind::kVelocityKick:
        kick = true;
        kick_size = v;
        kick_dir = a.direction_deg * kDeg;
        break;
      case AxisKind::kDisturbanceDirection:
        kick = true;
        kick_dir = v * kDeg;
        break;
    }
  }
  // A direction axis without a kick axis uses its own magnitude.
  const bool has_kick_axis = std::any_of(st.axes.begin(), st.axes.end(), [](const MapAxis& a) {
    return a.kind == AxisKind::kVelocityKick;
  });
  if (!has_kick_axis) {
    for (const MapAxis& a : st.axes)
      if (a.kind == AxisKind::kDisturbanceDirection) kick_size = a.magnitude;
  }
  if (kick)
    s.initial.velocity += kick_size * Eigen::Vector3d(std::cos(kick_dir), std::sin(kick_dir), 0);
}

// Stride-map spectral radius of a scene in its model (sim/simulate.hpp says how).
void stability_of(const scene::Scene& s, CellResult& c) {
  c.has_stability = true;
  const StabilityEstimate e = analyze_stability(s);
  c.spectral_radius = e.spectral_radius;
  c.stability_reason = e.ok ? "" : e.reason;
}

}  // namespace

scene::Scene scene_at(const MapStudy& st, double v0, double v1, scene::ModelKind model) {
  const double values[2] = {v0, v1};
  const bool any_pointer = std::any_of(st.axes.begin(), st.axes.end(), [](const MapAxis& a) {
    return a.kind == AxisKind::kPointer;
  });
  scene::Scene s;
  if (any_pointer) {
    json d = st.scene_doc;
    for (size_t i = 0; i < st.axes.size(); ++i)
      if (st.axes[i].kind == AxisKind::kPointer)
        d[json::json_pointer(st.axes[i].pointer)] = values[i];
    s = io::parse_scene(d, st.scene_file);
  } else {
    s = st.base_scene;
  }
  s.model = model;  // first: what a duty axis sets depends on the model
  apply_derived(st, values, s);
  return s;
}

std::uint64_t cell_seed_key(const MapStudy& st, long cell) {
  return static_cast<std::uint64_t>(st.seeding == Seeding::kRow ? cell_row(st, cell) : cell);
}

Scenario trial_scenario(const MapStudy& st, std::uint64_t key, long trial) {
  RandomScenarios spec = st.trials;
  spec.seed = mix_seed(st.trials.seed, key);
  return sample_scenario(spec, trial);
}

TrialOutcome run_trial(const MapStudy& st, const scene::Scene& cell_scene, const Scenario& trial) {
  const scene::Scene sc = apply_scenario(cell_scene, trial, st.trial_set);
  RunOptions opt;
  opt.record_trajectory = false;
  const reduced::RunResult run = simulate(sc, opt).run;
  const reduced::RunMetrics m = reduced::compute_metrics(sc, run, st.stabilized.settle);
  TrialOutcome t;
  t.status = std::string(reduced::to_string(run.status));
  t.strides = static_cast<long>(run.strides.size());
  t.settle_strides = m.settle_strides;
  t.duty_mean = std::isfinite(m.mean_duty) ? m.mean_duty : 0.0;
  t.peak_force = std::isfinite(m.peak_leg_force) ? m.peak_leg_force : 0.0;
  t.stabilized = run.status == reduced::RunStatus::kCompleted && m.settle_strides >= 0 &&
                 m.settle_strides <= st.stabilized.within_strides &&
                 t.strides - m.settle_strides >= st.stabilized.hold_strides;
  return t;
}

long stability_owner(const MapStudy& st, long cell) {
  const long row = cell_row(st, cell), col = cell_column(st, cell);
  const bool scene0 = is_scene_axis(st.axes[0]);
  const bool scene1 = st.axes.size() > 1 && is_scene_axis(st.axes[1]);
  return (scene1 ? row : 0) * st.columns() + (scene0 ? col : 0);
}

CellResult compute_cell(const MapStudy& st, long cell) {
  CellResult c;
  c.index = cell;
  const long row = cell_row(st, cell), col = cell_column(st, cell);
  const double v0 = st.axes[0].values[static_cast<size_t>(col)];
  const double v1 = st.axes.size() > 1 ? st.axes[1].values[static_cast<size_t>(row)] : 0.0;
  const std::uint64_t key = cell_seed_key(st, cell);
  c.trials.resize(st.models.size());
  for (size_t m = 0; m < st.models.size(); ++m) {
    const scene::Scene s = scene_at(st, v0, v1, st.models[m]);
    c.trials[m].reserve(static_cast<size_t>(st.trials.count));
    for (long t = 0; t < st.trials.count; ++t)
      c.trials[m].push_back(run_trial(st, s, trial_scenario(st, key, t)));
    if (st.stability && m + 1 == st.models.size() && stability_owner(st, cell) == cell)
      stability_of(s, c);
  }
  return c;
}

std::vector<CellSummary> summarize(const MapStudy& st, const std::vector<CellResult>& cells) {
  std::vector<CellSummary> out(cells.size());
  const size_t nm = st.models.size(), p = nm - 1;
  for (size_t i = 0; i < cells.size(); ++i) {
    const CellResult& c = cells[i];
    CellSummary& s = out[i];
    s.index = static_cast<long>(i);
    s.row = cell_row(st, s.index);
    s.column = cell_column(st, s.index);
    s.value0 = st.axes[0].values[static_cast<size_t>(s.column)];
    s.value1 = st.axes.size() > 1 ? st.axes[1].values[static_cast<size_t>(s.row)] : 0.0;
    const long n = st.trials.count;
    s.fraction.assign(nm, 0.0);
    long settled = 0, settle_sum = 0, fell = 0;
    double duty = 0.0;
    for (long t = 0; t < n; ++t) {
      for (size_t m = 0; m < nm; ++m)
        if (c.trials[m][static_cast<size_t>(t)].stabilized) s.fraction[m] += 1.0;
      const TrialOutcome& o = c.trials[p][static_cast<size_t>(t)];
      if (o.stabilized) {
        ++settled;
        settle_sum += o.settle_strides;
      }
      if (o.status != "completed") ++fell;
      duty += o.duty_mean;
      s.peak_force = std::max(s.peak_force, o.peak_force);
      if (nm == 2) {
        const bool a = c.trials[0][static_cast<size_t>(t)].stabilized;
        const bool b = c.trials[1][static_cast<size_t>(t)].stabilized;
        if (a && !b) ++s.a_only;
        if (b && !a) ++s.b_only;
      }
    }
    for (auto& f : s.fraction) f /= static_cast<double>(n);
    s.disagreements = s.a_only + s.b_only;
    s.mean_settle_strides =
        settled > 0 ? static_cast<double>(settle_sum) / static_cast<double>(settled) : -1.0;
    s.mean_duty = duty / static_cast<double>(n);
    s.fell_fraction = static_cast<double>(fell) / static_cast<double>(n);
    s.all_stabilized = settled == n;
    if (st.stability) {
      const CellResult& owner = cells[static_cast<size_t>(stability_owner(st, s.index))];
      s.spectral_radius = owner.spectral_radius;
    }
  }
  return out;
}

BoundaryResult initial_bracket(const MapStudy& st, const std::vector<CellSummary>& cells,
                               long row) {
  BoundaryResult b;
  b.row = row;
  const auto& v = st.axes[0].values;
  const long nc = st.columns();
  long last_good = -1;
  for (long c = nc - 1; c >= 0 && last_good < 0; --c)
    if (cells[static_cast<size_t>(row * nc + c)].all_stabilized) last_good = c;
  for (long c = 0; c < nc; ++c) {
    if (cells[static_cast<size_t>(row * nc + c)].all_stabilized) {
      b.first_good = v[static_cast<size_t>(c)];
      break;
    }
  }
  if (last_good == nc - 1) {
    b.status = "all_good";
    b.boundary = b.good = b.bad = v.back();
  } else if (last_good < 0) {
    b.status = "none_good";
    b.boundary = b.good = b.bad = v.front();
  } else {
    b.status = "bisected";
    b.good = b.boundary = v[static_cast<size_t>(last_good)];
    b.bad = v[static_cast<size_t>(last_good + 1)];
  }
  return b;
}

bool all_stabilized_at(const MapStudy& st, long row, double v, long probe) {
  const double v1 = st.axes.size() > 1 ? st.axes[1].values[static_cast<size_t>(row)] : 0.0;
  scene::Scene s;
  try {
    s = scene_at(st, v, v1, st.primary_model());
    check_buildable(s);
  } catch (const io::InputError&) {
    return false;  // a value between two valid grid values that makes no valid scene
  } catch (const std::invalid_argument&) {
    return false;  // ... or no robot the full model can build
  }
  const std::uint64_t key = st.seeding == Seeding::kRow
                                ? static_cast<std::uint64_t>(row)
                                : static_cast<std::uint64_t>(st.cells() + row * 1000 + probe);
  for (long t = 0; t < st.trials.count; ++t)
    if (!run_trial(st, s, trial_scenario(st, key, t)).stabilized) return false;
  return true;
}

bool next_probe(const MapStudy& st, const BoundaryResult& b, double* mid) {
  if (!(b.bad - b.good > st.resolution && b.probes < st.max_bisection_steps)) return false;
  *mid = st.axes[0].log_scale ? std::sqrt(b.good * b.bad) : 0.5 * (b.good + b.bad);
  return *mid > b.good && *mid < b.bad;  // false: no representable midpoint
}

BoundaryResult bisect_row(const MapStudy& st, BoundaryResult b) {
  if (b.status != "bisected") return b;
  for (double mid = 0.0; next_probe(st, b, &mid); ++b.probes) {
    if (all_stabilized_at(st, b.row, mid, b.probes))
      b.good = mid;
    else
      b.bad = mid;
  }
  b.boundary = b.good;
  return b;
}

json to_json(const CellResult& c) {
  json trials = json::array();
  for (const auto& per_model : c.trials) {
    json list = json::array();
    for (const TrialOutcome& t : per_model)
      list.push_back(
          {t.status, t.stabilized, t.settle_strides, t.strides, t.duty_mean, t.peak_force});
    trials.push_back(std::move(list));
  }
  json j = {{"cell", c.index}, {"trials", std::move(trials)}};
  if (c.has_stability) {
    j["spectral_radius"] = c.spectral_radius;
    j["stability_reason"] = c.stability_reason;
  }
  return j;
}

CellResult cell_from_json(const json& j) {
  CellResult c;
  c.index = j.at("cell").get<long>();
  for (const json& list : j.at("trials")) {
    std::vector<TrialOutcome> per_model;
    for (const json& t : list) {
      TrialOutcome o;
      o.status = t.at(0).get<std::string>();
      o.stabilized = t.at(1).get<bool>();
      o.settle_strides = t.at(2).get<long>();
      o.strides = t.at(3).get<long>();
      o.duty_mean = t.at(4).get<double>();
      o.peak_force = t.at(5).get<double>();
      per_model.push_back(std::move(o));
    }
    c.trials.push_back(std::move(per_model));
  }
  if (j.contains("spectral_radius")) {
    c.has_stability = true;
    c.spectral_radius = j.at("spectral_radius").get<double>();
    c.stability_reason = j.at("stability_reason").get<std::string>();
  }
  return c;
}

json to_json(const BoundaryResult& b) {
  return {{"row", b.row},   {"status", b.status}, {"boundary", b.boundary},
          {"good", b.good}, {"bad", b.bad},       {"probes", b.probes}};
}

BoundaryResult boundary_from_json(const json& j) {
  BoundaryResult b;
  b.row = j.at("row").get<long>();
  b.status = j.at("status").get<std::string>();
  b.boundary = j.at("boundary").get<double>();
  b.good = j.at("good").get<double>();
  b.bad = j.at("bad").get<double>();
  b.probes = j.at("probes").get<long>();
  return b;
}

}  // namespace pronk::optimize::map
