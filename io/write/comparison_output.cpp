#include "io/write/comparison_output.hpp"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

#include "io/build_info.hpp"
#include "io/write/atomic_file.hpp"
#include "io/write/run_output.hpp"
#include "io/write/table.hpp"

namespace pronk::io {

namespace {

using nlohmann::json;

// Every bit, as the other CSV outputs (table_csv).
std::string full(double v) { return exact_number(v); }

// For reading: 6 significant digits.
std::string short_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A text field of a CSV file that has no quoting: a separator or line break becomes harmless.
std::string csv_field(const std::string& text) {
  std::string out = text;
  for (char& ch : out) {
    if (ch == ',') ch = ';';
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  return out;
}

std::optional<double> find(const std::map<std::string, double>& m, const std::string& k) {
  const auto it = m.find(k);
  return it == m.end() ? std::nullopt : std::optional<double>(it->second);
}

// An objective term "mean(m)" that repeats the row m for every design says nothing new.
bool repeats_its_metric(const ComparisonSet& s, const std::string& k) {
  if (k.size() <= 6 || k.rfind("mean(", 0) != 0 || k.back() != ')') return false;
  const std::string m = k.substr(5, k.size() - 6);
  for (const auto& metrics : s.metrics) {
    if (find(metrics, m) != find(metrics, k)) return false;
  }
  return true;
}

// The number of each design's trials with each outcome, best outcome first.
std::vector<std::pair<std::string, std::vector<long>>> outcome_counts(const ComparisonSet& s) {
  std::vector<std::pair<std::string, std::vector<long>>> out;
  for (const char* o : {"stabilized", "completed", "fell", "diverged", "failed"}) {
    std::vector<long> n(s.trials.size(), 0);
    for (size_t d = 0; d < s.trials.size(); ++d) {
      for (const ComparisonTrial& t : s.trials[d]) n[d] += t.outcome == o ? 1 : 0;
    }
    out.emplace_back(o, n);
  }
  return out;
}

std::string md_row(const std::vector<std::string>& cells) {
  std::string out = "|";
  for (const std::string& c : cells) {
    out += ' ';
    out += c;
    out += " |";
  }
  out += '\n';
  return out;
}

std::string md_head(const std::string& first, const ComparisonData& c) {
  std::vector<std::string> head = {first};
  std::string rule = "|---|";
  for (const auto& d : c.designs) {
    head.push_back(d.label);
    rule += "---|";
  }
  return md_row(head) + rule + "\n";
}

std::string designs_md(const ComparisonData& c) {
  std::ostringstream md;
  md << "| design | file | study | scene | its study's model | run here in | on its own "
        "study's trials |\n|---|---|---|---|---|---|---|\n";
  for (const auto& d : c.designs) {
    md << md_row({d.label, "`" + d.file + "`", d.study, d.scene, d.own_model, d.model,
                  d.own_study ? "yes: the numbers design.json records" : "no"});
  }
  return md.str();
}

std::string parameters_md(const ComparisonData& c) {
  std::vector<std::string> names;  // every design's parameters, first appearance first
  for (const auto& d : c.designs) {
    for (const auto& [n, v] : d.parameters) {
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    }
  }
  std::ostringstream md;
  md << "Each design runs its own scene with its own parameter values (– : not a parameter of "
        "its study):\n\n"
     << md_head("parameter", c);
  for (const std::string& n : names) {
    std::vector<std::string> row = {n};
    for (const auto& d : c.designs) {
      std::string cell = "–";
      for (const auto& [pn, v] : d.parameters) {
        if (pn == n) cell = short_number(v);
      }
      row.push_back(cell);
    }
    md << md_row(row);
  }
  return md.str();
}

// The trials on which the designs' outcomes differ (at most `limit` listed).
std::string disagreements_md(const ComparisonData& c, const ComparisonSet& s, size_t limit) {
  std::vector<std::string> lines;
  long count = 0;
  for (size_t t = 0; t < s.trial_names.size(); ++t) {
    std::set<std::string> seen;
    std::string what;
    for (size_t d = 0; d < s.trials.size(); ++d) {
      seen.insert(s.trials[d][t].outcome);
      what += (d ? ", " : "") + c.designs[d].label + " " + s.trials[d][t].outcome;
    }
    if (seen.size() < 2) continue;
    ++count;
    if (lines.size() < limit) {
      lines.push_back("- " + std::to_string(t) + " (" + s.trial_names[t] + "): " + what + "\n");
    }
  }
  if (count == 0) return "The designs' outcomes agree on every trial.\n";
  std::string out = "Trials whose outcomes differ (" + std::to_string(count) + " of " +
                    std::to_string(s.trial_names.size()) + "; every trial in `trials.csv`):\n\n";
  for (const auto& l : lines) out += l;
  if (static_cast<size_t>(count) > lines.size()) {
    out += "- and " + std::to_string(count - static_cast<long>(lines.size())) + " more\n";
  }
  return out;
}

std::string set_md(const ComparisonData& c, const ComparisonSet& s,
                   const std::vector<ComparisonRow>& rows) {
  std::ostringstream md;
  md << "\n## " << (s.name == "validation" ? "Validation set" : "Scenarios") << ": "
     << s.description << "\n\n";
  for (size_t d = 0; d < s.failure.size(); ++d) {
    if (!s.failure[d].empty()) {
      md << "**" << c.designs[d].label << " did not run:** " << s.failure[d] << "\n\n";
    }
  }
  md << md_head("metric", c);
  for (const ComparisonRow& r : rows) {
    if (r.set != s.name) continue;
    std::vector<std::string> row = {r.metric};
    for (const auto& v : r.values) row.push_back(v ? short_number(*v) : "–");
    md << md_row(row);
  }
  md << "\nOutcomes (trials):\n\n" << md_head("outcome", c);
  for (const auto& [outcome, counts] : outcome_counts(s)) {
    long any = 0;
    for (long n : counts) any += n;
    if (any == 0) continue;
    std::vector<std::string> row = {outcome};
    for (long n : counts) row.push_back(std::to_string(n));
    md << md_row(row);
  }
  md << "\n" << disagreements_md(c, s, 20);
  return md.str();
}

std::string playback_text(const ComparisonData& c) {
  if (c.playback_set == "nominal") {
    return "the nominal trial (the design's scene undisturbed, the nominal robot)";
  }
  return c.playback_set + " trial " + std::to_string(c.playback_index) + " (" + c.playback_name +
         ")";
}

}  // namespace

const std::vector<std::string>& comparison_trial_metrics() {
  static const std::vector<std::string> names = {"apex_held", "hop_height_error", "x_error",
                                                 "y_error",   "attitude_error",   "settle_strides",
                                                 "duty_mean", "final_error"};
  return names;
}

std::vector<ComparisonRow> comparison_rows(const ComparisonData& c) {
  std::vector<ComparisonRow> rows;
  for (const ComparisonSet& s : c.sets) {
    rows.push_back({s.name, "cost", {}});
    rows.back().values = s.cost;
    std::set<std::string> names;
    for (const auto& m : s.metrics) {
      for (const auto& [k, v] : m) names.insert(k);
    }
    for (const std::string& k : names) {
      if (k == "spectral_radius" && !c.stability) continue;
      if (repeats_its_metric(s, k)) continue;
      ComparisonRow r{s.name, k, {}};
      for (const auto& m : s.metrics) r.values.push_back(find(m, k));
      rows.push_back(std::move(r));
    }
  }
  return rows;
}

std::string comparison_metrics_csv(const ComparisonData& c) {
  std::string out = "set,metric";
  for (const auto& d : c.designs) {
    out += ',';
    out += d.label;
  }
  out += '\n';
  for (const ComparisonRow& r : comparison_rows(c)) {
    out += r.set;
    out += ',';
    out += r.metric;
    for (const auto& v : r.values) {
      out += ',';
      if (v) out += full(*v);
    }
    out += '\n';
  }
  return out;
}

std::string comparison_trials_csv(const ComparisonData& c) {
  const auto& keys = comparison_trial_metrics();
  std::string out = "set,index,name";
  for (const auto& d : c.designs) {
    out += ',';
    out += d.label;
    out += ".outcome";
    for (const std::string& k : keys) {
      out += ',';
      out += d.label;
      out += '.';
      out += k;
    }
  }
  out += '\n';
  for (const ComparisonSet& s : c.sets) {
    for (size_t t = 0; t < s.trial_names.size(); ++t) {
      out += s.name;
      out += ',';
      out += std::to_string(t);
      out += ',';
      out += csv_field(s.trial_names[t]);
      for (const auto& trials : s.trials) {
        out += ',';
        out += trials[t].outcome;
        for (const std::string& k : keys) {
          out += ',';
          if (const auto v = find(trials[t].metrics, k)) out += full(*v);
        }
      }
      out += '\n';
    }
  }
  return out;
}

std::string comparison_summary_md(const ComparisonData& c) {
  std::ostringstream md;
  md << "# Comparison of " << c.designs.size() << " designs\n\n";
  md << "Every design ran the same trials: those of the study of `" << c.reference_file << "` (`"
     << c.reference_study << "`)";
  for (const ComparisonSet& s : c.sets) md << "; " << s.name << ": " << s.description;
  md << ". Each cost is that study's objective; each design runs its own scene with its own "
        "parameter values, "
     << (c.model.empty() ? "in its own study's model" : "in the " + c.model + " model") << ".\n\n";
  md << designs_md(c);
  if (!c.notes.empty()) {
    md << "\n";
    for (const std::string& n : c.notes) md << "- " << n << "\n";
  }
  const std::vector<ComparisonRow> rows = comparison_rows(c);
  for (auto it = c.sets.rbegin(); it != c.sets.rend(); ++it) md << set_md(c, *it, rows);
  md << "\n## Parameters\n\n" << parameters_md(c);
  md << "\n## Playback\n\nEach design on " << playback_text(c) << ":";
  for (const auto& d : c.designs) {
    if (d.run_dir.empty()) {
      md << " " << d.label << " (no run)";
    } else {
      md << " [" << d.label << "](" << d.run_dir << "/view.html)";
    }
  }
  md << " (`report.html` plays them side by side).\n\nFiles: `compare.csv` (every metric, one "
        "column per design), `trials.csv` (every trial's outcome and metrics), "
        "`compare.json`, `report.html`, `runs/`.\n";
  return md.str();
}

json comparison_json(const ComparisonData& c) {
  json designs = json::array();
  for (const auto& d : c.designs) {
    json params = json::object();
    for (const auto& [n, v] : d.parameters) params[n] = v;
    designs.push_back({{"label", d.label},
                       {"file", d.file},
                       {"study", d.study},
                       {"scene", d.scene},
                       {"own_model", d.own_model},
                       {"model", d.model},
                       {"own_study", d.own_study},
                       {"parameters", params},
                       {"run", d.run_dir}});
  }
  json sets = json::array();
  for (const ComparisonSet& s : c.sets) {
    sets.push_back({{"name", s.name},
                    {"description", s.description},
                    {"trials", s.trial_names.size()},
                    {"failure", s.failure}});
  }
  return {{"type", "pronk_comparison"},
          {"version", pronk::version()},
          {"commit", pronk::git_commit()},
          {"reference", {{"file", c.reference_file}, {"study", c.reference_study}}},
          {"model", c.model},
          {"stability", c.stability},
          {"designs", designs},
          {"sets", sets},
          {"playback",
           {{"set", c.playback_set},
            {"index", c.playback_index},
            {"name", c.playback_name},
            {"description", playback_text(c)}}},
          {"notes", c.notes}};
}

void write_comparison_files(const std::string& dir, const ComparisonData& c) {
  make_directories(dir);
  write_file_atomic(dir + "/compare.csv", comparison_metrics_csv(c));
  write_file_atomic(dir + "/trials.csv", comparison_trials_csv(c));
  write_file_atomic(dir + "/summary.md", comparison_summary_md(c));
  write_file_atomic(dir + "/compare.json", dump_checked(comparison_json(c)));
}

}  // namespace pronk::io
