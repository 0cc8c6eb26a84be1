// The studies the optimizer benchmarks run (bench_pagmo, bench_moo): study 2's problem
// (legged pulse model) and study 3's full-model stage cut down to 8 trials of 2 s.
#pragma once

#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "optimize/staged_study.hpp"
#include "optimize/study.hpp"

namespace pronk::bench {

using pronk::optimize::Study;

/// Study 2 with pagmo's `algorithm`, `population` per generation, `generations` of them.
inline Study study2_problem(const std::string& algorithm, int population, int generations) {
  return optimize::load_study(
      std::string(PRONK_SOURCE_DIR) + "/studies/study2_pagmo_cmaes.json",
      {"/optimizer/algorithm=" + algorithm,
       "/optimizer/options={\"population\": " + std::to_string(population) + "}",
       "/optimizer/max_evaluations=" + std::to_string(population * generations)});
}

/// Study 3's full-model stage, started where its committed pulse stage ended
/// (results/study3_full_model_running/design.json), tuned by pagmo, on 8 of its trials cut
/// to 2 s (an evaluation costs about 0.4 s of one core instead of 5.6 s).
inline Study full_model_problem(const std::string& algorithm, int population, int generations) {
  const std::string dir = std::string(PRONK_SOURCE_DIR) + "/studies/";
  const std::string file = dir + "study3_full_model_running.json";
  std::ifstream in(file);
  nlohmann::json doc = nlohmann::json::parse(in);
  nlohmann::json& stage = doc.at("stages").at(1);
  stage["optimizer"] = {{"library", "pagmo"},
                        {"algorithm", algorithm},
                        {"max_evaluations", population * generations},
                        {"seed", 3},
                        {"options", {{"population", population}}}};
  stage["scenarios"] = doc.at("scenarios");
  stage["scenarios"]["duration"] = 2.0;
  stage["scenarios"]["random"]["count"] = 8;
  std::ifstream recorded(std::string(PRONK_SOURCE_DIR) +
                         "/results/study3_full_model_running/design.json");
  const std::map<std::string, double> pulse_stage =
      nlohmann::json::parse(recorded).at("stages").at(0).at("parameters");
  return optimize::stage_study(optimize::parse_staged_study(doc, file, dir), 1, pulse_stage);
}

}  // namespace pronk::bench
