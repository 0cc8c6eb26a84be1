// The page data of a multi-objective study directory: pareto.json (the front, its validation,
// the hypervolume per generation, the knee), every evaluation's objectives from journal.jsonl,
// and each front design's playback run (front/<k>/, when written).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/load/input_error.hpp"
#include "io/load/json_reader.hpp"
#include "io/load/scene_loader.hpp"
#include "io/page/page_data.hpp"

namespace pronk::io::page {

namespace {

// Numbers of all the front's playbacks together, and at least per design.
constexpr long kFrontPlaybackCells = 240000;
constexpr long kFrontPlaybackMin = 8000;

// An objective's terms as text: "mean(stabilized) x -1 + ...".
std::string terms_text(const nlohmann::json& objective) {
  std::string out;
  for (const nlohmann::json& t : objective.value("terms", nlohmann::json::array())) {
    if (!out.empty()) out += " + ";
    const double w = t.value("weight", 1.0);
    out += t.value("aggregate", std::string("mean")) + "(" + t.value("metric", std::string()) + ")";
    if (w != 1.0) {
      char buf[32];
      std::snprintf(buf, sizeof buf, " x %g", w);
      out += buf;
    }
  }
  return out;
}

// Every evaluation's objectives, one array per objective (null where an evaluation has none:
// a failed one), and whether it met every constraint, from the journal's lines.
nlohmann::json journal_objectives(const std::string& dir, size_t objectives) {
  nlohmann::json cols = nlohmann::json::array();
  for (size_t j = 0; j < objectives; ++j) cols.push_back(nlohmann::json::array());
  nlohmann::json feasible = nlohmann::json::array();
  std::ifstream in(dir + "/journal.jsonl");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    nlohmann::json r = nlohmann::json::parse(line, nullptr, false);
    if (r.is_discarded() || !r.is_object() || !r.contains("index")) continue;  // header, torn tail
    const nlohmann::json f = r.value("objectives", nlohmann::json::array());
    for (size_t j = 0; j < objectives; ++j) {
      cols[j].push_back(j < f.size() && f[j].is_number() ? f[j] : nlohmann::json(nullptr));
    }
    bool ok = !r.contains("failure");
    for (const nlohmann::json& g : r.value("constraints", nlohmann::json::array())) {
      ok = ok && g.is_number() && g.get<double>() <= 1e-8;
    }
    feasible.push_back(ok);
  }
  return {{"objectives", cols}, {"feasible", feasible}};
}

// One front design as the page shows it.
nlohmann::json front_entry(const nlohmann::json& d, const nlohmann::json& names,
                           const nlohmann::json& constraint_names) {
  nlohmann::json objectives = nlohmann::json::array();
  for (const nlohmann::json& n : names) objectives.push_back(d.at("objectives").at(n.get<std::string>()));
  nlohmann::json constraints = nlohmann::json::object();
  const nlohmann::json& g = d.value("constraints", nlohmann::json::array());
  for (size_t j = 0; j < g.size() && j < constraint_names.size(); ++j) {
    constraints[constraint_names[j].get<std::string>()] = g[j];
  }
  nlohmann::json validation = nullptr;
  if (d.contains("validation") && d["validation"].is_object()) {
    const nlohmann::json& v = d["validation"];
    validation = {{"trials", v.value("scenarios", 0)},
                  {"stabilized", v.value("stabilized", 0.0)},
                  {"fell", v.value("fell", 0.0)}};
    const nlohmann::json& vo = v.value("objectives", nlohmann::json::array());
    for (size_t j = 0; j < names.size() && j < vo.size(); ++j) {
      validation[names[j].get<std::string>()] = vo[j];
    }
  }
  return {{"evaluation", d.at("evaluation")},
          {"parameters", d.at("parameters")},
          {"objectives", objectives},
          {"constraints", constraints},
          {"feasible", true},  // the front holds feasible designs only
          {"validation", validation}};
}

}  // namespace

nlohmann::json pareto_page_data(const std::string& dir) {
  const std::string file = dir + "/pareto.json";
  const nlohmann::json p = read_json_file(file);
  if (!io::holds(p, "type", "pronk_pareto")) {
    throw InputError(file, "/type", "\"pronk_pareto\"", "something else");
  }
  const nlohmann::json& names = p.at("objective_names");
  const nlohmann::json& study = p.at("study_document");
  nlohmann::json objectives = nlohmann::json::array();
  const nlohmann::json& defs = study.value("objectives", nlohmann::json::array());
  for (size_t j = 0; j < names.size(); ++j) {
    objectives.push_back({{"name", names[j]},
                          {"description", j < defs.size() ? terms_text(defs[j]) : std::string()}});
  }
  const nlohmann::json& opt = p.at("optimizer");
  const long population = opt.value("population", 0L);
  nlohmann::json hv = nlohmann::json::array();
  const nlohmann::json& h = p.value("hypervolume", nlohmann::json::array());
  for (size_t g = 0; g < h.size(); ++g) hv.push_back({{"generation", g}, {"value", h[g]}});
  nlohmann::json front = nlohmann::json::array();
  for (const nlohmann::json& d : p.at("front")) {
    front.push_back(front_entry(d, names, p.value("constraint_names", nlohmann::json::array())));
  }
  char algorithm[160];
  std::snprintf(algorithm, sizeof algorithm, "%s (pagmo), population %ld, %ld generations",
                opt.value("algorithm", std::string("?")).c_str(), population,
                opt.value("generations", 0L));
  nlohmann::json pareto = {{"name", p.value("study", std::string("study"))},
                           {"algorithm", algorithm},
                           {"objectives", objectives},
                           {"evaluations", journal_objectives(dir, names.size())},
                           {"front", front},
                           {"knee", p.value("knee", -1L)},
                           {"reference", p.value("reference", nlohmann::json::array())},
                           {"hypervolume", hv},
                           {"validation_metrics", {"stabilized", "fell"}},
                           {"playback", "each design on the study's first trial"}};
  nlohmann::json out = {{"kind", "pareto"}, {"pareto", pareto}, {"runs", nlohmann::json::array()}};
  const long cells = std::max(kFrontPlaybackMin,
                              kFrontPlaybackCells / std::max<long>(1, static_cast<long>(front.size())));
  for (size_t k = 0; k < front.size(); ++k) {
    const std::string run = dir + "/front/" + std::to_string(k);
    std::error_code ec;
    out["runs"].push_back(std::filesystem::is_directory(run, ec) ? run_page_data(run, cells)
                                                                 : nlohmann::json(nullptr));
  }
  return out;
}

}  // namespace pronk::io::page
