#pragma once
// An observer grid's glare terms in the results JSON (`observer_grid.glare_terms`, written with
// contributions) and read back by `rescale` (docs/glare.md, "Rescaling an observer grid").
#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "glare/observer_grid.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// `glare_terms`: luminaires, not_rated, one status string and one terms array per point.
nlohmann::json glare_terms_json(const GlareTerms& terms);

/// The positions, view directions and glare terms of observer grid target `target` (a results
/// target); InputError naming the field when any is missing, short or out of range.
ObserverGridGeometry read_observer_grid_geometry(const JsonNode& target);

}  // namespace lightsolver::detail
