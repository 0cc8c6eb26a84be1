#include "optimize/compare_output.hpp"

#include <cstdio>
#include <filesystem>

#include "io/load/input_error.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/simulation_output.hpp"
#include "sim/run/count_text.hpp"
#include "sim/simulate.hpp"

namespace pronk::optimize {

namespace {

using nlohmann::json;

std::string model_of(const Study& s) { return s.evaluator.scene_doc.value("model", std::string()); }

// "64 trials of 20 s (64 random, seed 6402; the robot perturbed)", from the set as parsed and
// its study entry.
std::string set_description(const ScenarioSet& set, const json& entry) {
  const size_t n = set.scenarios.size();
  char length[64];
  if (set.strides > 0) {
    std::snprintf(length, sizeof length, "at most %g s or %ld strides", set.duration, set.strides);
  } else {
    std::snprintf(length, sizeof length, "%g s", set.duration);
  }
  std::string out = run::count_text(n, "trial") + " of " + length;
  std::string parts;
  if (entry.contains("list") && entry["list"].is_array()) {
    parts = std::to_string(entry["list"].size()) + " listed";
  }
  if (entry.contains("random") && entry["random"].is_object()) {
    const json& r = entry["random"];
    parts += parts.empty() ? "" : ", ";
    parts += std::to_string(r.value("count", 0L)) + " random, seed " +
             std::to_string(r.value("seed", 1ULL));
  }
  if (perturbs_robot(set)) parts += "; the robot perturbed";
  return out + " (" + parts + ")";
}

// A design's outcome of one trial.
io::ComparisonTrial trial_outcome(const ScenarioOutcome& s) {
  io::ComparisonTrial t;
  t.metrics = s.metrics;
  if (s.status != "completed") {
    t.outcome = s.status;  // fell, diverged
  } else {
    const auto it = s.metrics.find("stabilized");
    t.outcome = it != s.metrics.end() && it->second != 0.0 ? "stabilized" : "completed";
  }
  return t;
}

// One set as every design ran it.
io::ComparisonSet comparison_set(const Comparison& c, bool validation) {
  const Study& ref = c.designs.front().judged;  // every design runs the same trials
  const ScenarioSet& set = validation ? *ref.validation : ref.evaluator.scenarios;
  io::ComparisonSet out;
  out.name = validation ? "validation" : "scenarios";
  out.description = set_description(set, ref.document.at(out.name));
  for (const Scenario& s : set.scenarios) out.trial_names.push_back(s.name);
  for (const ComparedDesign& d : c.designs) {
    const Evaluation& e = validation ? *d.evaluation.validation : d.evaluation.scenarios;
    out.cost.push_back(e.ok ? std::optional<double>(e.cost) : std::nullopt);
    out.metrics.push_back(e.ok ? e.aggregated : MetricMap{});
    out.failure.push_back(e.ok ? "" : e.failure);
    std::vector<io::ComparisonTrial> trials;
    for (size_t t = 0; t < set.scenarios.size(); ++t) {
      trials.push_back(e.ok && t < e.scenarios.size() ? trial_outcome(e.scenarios[t])
                                                      : io::ComparisonTrial{"failed", {}});
    }
    out.trials.push_back(std::move(trials));
  }
  return out;
}

io::ComparisonColumn comparison_column(const ComparedDesign& d) {
  io::ComparisonColumn col;
  col.label = d.label;
  col.file = d.file;
  col.study = d.recorded.study.name;
  col.scene = d.recorded.study.evaluator.scene_doc.value("name", std::string());
  col.own_model = model_of(d.recorded.study);
  col.model = model_of(d.judged);
  col.own_study = d.own_study;
  const auto& params = d.recorded.study.evaluator.parameters;
  const std::vector<double> values = physical_values(params, d.recorded.unit);
  for (size_t i = 0; i < params.size(); ++i) col.parameters.emplace_back(params[i].name, values[i]);
  col.run_dir = "runs/" + d.label;
  return col;
}

}  // namespace

void check_comparison_directory(const std::string& dir) {
  for (const char* f : {"design.json", "journal.jsonl", "history.csv", "cells.csv",
                        "trajectory.csv", "nodes.csv"}) {
    std::error_code ec;
    if (std::filesystem::exists(dir + "/" + f, ec)) {
      throw io::InputError("--out", "",
                           "a new directory or one `pronk compare` wrote (it writes summary.md "
                           "and report.html there)",
                           "\"" + dir + "\", which holds another command's " + f);
    }
  }
}

io::ComparisonData comparison_data(const Comparison& c) {
  io::ComparisonData out;
  out.reference_file = c.reference_file;
  out.reference_study = c.reference_study;
  out.model = c.model;
  out.stability = c.designs.front().judged.evaluator.stability;
  for (const ComparedDesign& d : c.designs) out.designs.push_back(comparison_column(d));
  out.sets.push_back(comparison_set(c, false));
  if (c.designs.front().judged.validation) out.sets.push_back(comparison_set(c, true));
  out.playback_set = c.playback.set;
  out.playback_index = c.playback.index;
  out.playback_name = c.playback.name;
  out.notes = c.notes;
  return out;
}

io::ComparisonData write_comparison(const std::string& dir, const Comparison& c) {
  io::ComparisonData data = comparison_data(c);
  io::make_directories(dir + "/runs");
  for (size_t k = 0; k < c.designs.size(); ++k) {
    scene::Scene s;
    try {
      s = playback_scene(c, k);
    } catch (const io::InputError& e) {
      data.notes.push_back(c.designs[k].label + " has no playback: " + e.what());
      data.designs[k].run_dir.clear();
      continue;
    }
    const RunResult r = simulate(s);
    io::write_simulation_outputs(dir + "/" + data.designs[k].run_dir, s, r,
                                 reduced::compute_metrics(s, r.run));
  }
  io::write_comparison_files(dir, data);
  return data;
}

}  // namespace pronk::optimize
