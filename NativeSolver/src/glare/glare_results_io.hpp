#pragma once
// Glare read back from a results document (`rescale`, docs/glare.md "Rescaling an observer
// grid"): an observer grid's geometry and glare terms, a plain observer's luminaires, each
// luminance dimmed by its group's factor. The hooks of core/results_glare.hpp.
#include <memory>
#include <string>

#include "core/json_reader.hpp"
#include "core/results_glare.hpp"
#include "glare/observer_grid.hpp"

namespace lightsolver::detail {

/// The positions, view directions and glare terms of observer grid target `target` (a results
/// target); InputError naming the field when any is missing, short or out of range.
ObserverGridGeometry read_observer_grid_geometry(const JsonNode& target);

/// ResultsGlare::observer_grid: read_observer_grid_geometry, dimmed by `factors`.
std::shared_ptr<const ObserverGridGeometry> dimmed_observer_grid(const JsonNode& target,
                                                                 const LuminaireFactors& factors);

/// ResultsGlare::points.
std::size_t observer_grid_points(const ObserverGridGeometry& geometry);

/// ResultsGlare::observer: the observer's luminaires in the results as one eye's glare terms,
/// dimmed, rated by the statistics step traced runs use (eye_glare).
ObserverGlare dimmed_observer_glare(const JsonNode& target, const LuminaireFactors& factors,
                                    const std::string& name, const Estimate& indirect);

}  // namespace lightsolver::detail
