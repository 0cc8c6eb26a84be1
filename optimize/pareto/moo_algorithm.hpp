// How the pagmo algorithm of a multi-objective run is built. Internal to optimize/pareto (it
// includes pagmo's headers); the public side is moo_options.hpp and moo_driver.hpp.
#pragma once

#include <pagmo/algorithm.hpp>
#include <pagmo/bfe.hpp>

#include "optimize/pareto/moo_options.hpp"

namespace pronk::optimize::pareto::detail {

/// Whether the algorithm evaluates a generation through a pagmo batch evaluator (nsga2 and
/// nspso: one batch per generation) rather than point by point (moead).
bool moo_native_batch(const MooOptions& options);

/// The pagmo algorithm of `options` (validated) for one generation per evolve() call, its
/// random state kept between calls, seeded with `seed`; `batch` (nsga2, nspso; may be null)
/// becomes its batch evaluator. Throws what pagmo's constructor throws.
pagmo::algorithm make_moo_algorithm(const MooOptions& options, unsigned seed,
                                    const pagmo::bfe* batch);

}  // namespace pronk::optimize::pareto::detail
