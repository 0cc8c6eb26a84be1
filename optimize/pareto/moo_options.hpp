// The options of a multi-objective run (moo_driver.hpp): which of pagmo's multi-objective
// algorithms, its population, generations and seed, and its own options by name with pagmo's
// defaults. Checked by validate(), whose messages read "field: value: rule" as the pagmo
// settings of single-objective studies do (optimize/pagmo_algorithms.hpp).
//
// The algorithms (pagmo 2.18) and their own options, with pagmo's defaults:
//   nsga2  NSGA-II (Deb et al. 2002). Population a multiple of 4, at least 8 (pagmo: at
//          least 5 and a multiple of 4). cr 0.95 in [0, 1), eta_c 10 in [1, 100],
//          m 0.01 in [0, 1], eta_m 50 in [1, 100].
//   moead  MOEA/D-DE (Zhang & Li 2007; Li & Zhang 2009). weight_generation "grid" or
//          "low discrepancy" (pagmo's "random" is not offered: pronk evolves one generation
//          per call and pagmo draws the random weights anew at every call), decomposition
//          "tchebycheff" | "weighted" | "bi", neighbours 20 (integer >= 2, at most
//          population - 1), CR 1 in [0, 1], F 0.5 in [0, 1], eta_m 20 in [0, 1e6], realb 0.9
//          in [0, 1], limit 2 (integer >= 0), preserve_diversity true. Population at least the
//          objective count and neighbours + 1; with "grid" weights, a size the simplex grid
//          of that many objectives has (any size for 2 objectives; 3, 6, 10, 15, 21, ... for 3).
//   nspso  NSPSO (Li 2003). omega 0.6 in [0, 1], c1 2 and c2 2 and chi 1 in (0, 1e6],
//          v_coeff 0.5 in (0, 1], leader_selection_range 60 (integer in [1, 100]),
//          diversity_mechanism "crowding distance" | "niche count" | "max min".
//          Population at least 2. pagmo's memory flag is always on (velocities and the
//          particles' best points are kept from one generation to the next).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pronk::optimize::pareto {

struct MooOptions {
  std::string algorithm = "nsga2";  ///< "nsga2", "moead" or "nspso"
  long population = 100;            ///< individuals (evaluations) per generation
  long generations = 100;           ///< generations after the first population, >= 1
  std::uint64_t seed = 1;           ///< fixes the first population and the algorithm's draws
  /// The algorithm's own options by name (numbers, booleans, words as listed above); an
  /// absent option takes pagmo's default.
  nlohmann::json options = nlohmann::json::object();
  /// The hypervolume reference point, one value per objective; empty: reference_point()
  /// (front.hpp) of the first population, fixed for the whole run.
  std::vector<double> reference;
  /// Points the first population starts with (a known design, for example), the rest of it
  /// drawn uniformly from the seed as usual; at most `population`, each inside the box.
  std::vector<std::vector<double>> initial_points;

  /// Every problem found, each "field: value: rule" (field "algorithm", "population",
  /// "generations", "objectives", "reference" or "options/NAME"); empty when the options
  /// are valid for a problem of `objectives` objectives.
  std::vector<std::string> validate(long objectives) const;
};

/// Names of the algorithms, in the order the docs list them.
const std::vector<std::string>& moo_algorithm_names();

}  // namespace pronk::optimize::pareto
