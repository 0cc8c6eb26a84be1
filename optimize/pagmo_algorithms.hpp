// The pagmo2 algorithms pronk offers, their options and how each is built: the
// table behind `"library": "pagmo"`. Internal to the pagmo driver (it includes
// pagmo's headers); the public side is optimize/pagmo_driver.hpp.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pagmo/algorithm.hpp>
#include <pagmo/bfe.hpp>

namespace pronk::optimize::detail {

/// A pagmo algorithm with its options checked and defaults filled in.
struct PagmoSettings {
  std::string algorithm;  ///< "cmaes", "xnes", "de", "sade", "de1220" or "pso_gen"
  long population = 20;   ///< individuals per generation (evaluations per generation)
  long generations = 0;   ///< cap on generations; 0 = as many as max_evaluations allows
  /// Stop (converged) when the population's cost spread |f_worst - f_best| < ftol (0 = off).
  double ftol = 0.0;
  /// Stop (converged) when sum_j |x_worst,j - x_best,j| < xtol, in the driver's
  /// coordinates (a study's are [0, 1] per parameter); 0 = off.
  double xtol = 1e-6;
  /// The algorithm's own numeric options that were given (absent: pagmo's default or
  /// automatic value).
  std::map<std::string, double> numbers;
  std::vector<unsigned> allowed_variants;  ///< de1220's mutation variants
};

/// Names of the algorithms, in the order the docs list them.
const std::vector<std::string>& pagmo_algorithm_names();

/// Checks `options` (the study's "optimizer"/"options" object) for `algorithm` and fills
/// *settings. On failure writes "field: value: rule" into *error (field "algorithm" or
/// "options/NAME"), as OptimizerOptions::validate does. `max_evaluations` must hold at
/// least the first population.
bool parse_pagmo_settings(const std::string& algorithm, const nlohmann::json& options,
                          long max_evaluations, PagmoSettings* settings, std::string* error);

/// Whether the algorithm evaluates its population through a pagmo batch evaluator
/// (pso_gen): it then runs as one evolve() call over every generation. The others run
/// one generation per evolve() call, with their state kept between calls.
bool pagmo_native_batch(const PagmoSettings& settings);

/// Whether every point of one generation is fixed by the state at the generation's start
/// (true for every configuration but self-adaptation variant 2 of sade and de1220, whose
/// trial points read F and CR that earlier trials of the same generation changed): the
/// driver then evaluates the generation as one batch, otherwise point by point.
bool pagmo_independent_generation(const PagmoSettings& settings);

/// The pagmo algorithm for `generations` generations per evolve() call, seeded, with
/// pagmo's own tolerances off (the driver tests ftol and xtol itself), box bounds enforced
/// (cmaes, xnes) and adapted state kept between calls ("memory"). `batch` is set as the
/// batch evaluator of a native-batch algorithm (nullptr for the others).
pagmo::algorithm make_pagmo_algorithm(const PagmoSettings& settings, unsigned generations,
                                      unsigned seed, const pagmo::bfe* batch);

}  // namespace pronk::optimize::detail
