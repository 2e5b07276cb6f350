#pragma once
// An observer grid's glare terms in the results JSON (`observer_grid.glare_terms`, written with
// contributions); `rescale` reads them back through glare (glare/glare_results_io.hpp, above
// core: docs/solver.md, "Layers").
#include <nlohmann/json.hpp>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// `glare_terms`: luminaires, not_rated, one status string and one terms array per point.
nlohmann::json glare_terms_json(const GlareTerms& terms);

}  // namespace lightsolver::detail
