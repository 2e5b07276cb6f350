#pragma once
// Glare read back from results (`rescale`, docs/glare.md "Rescaling an observer grid"): an
// observer grid's geometry and glare terms, a plain observer's luminaires, each luminance dimmed
// by its group's factor. The hooks of results/results_glare.hpp.
#include <memory>
#include <string>

#include "results/results_glare.hpp"
#include "glare/observer_grid.hpp"

namespace lightsolver::detail {

/// ResultsGlare::observer_grid: the grid's geometry and terms, dimmed by `factors`.
std::shared_ptr<const ObserverGridGeometry> dimmed_observer_grid(const ObserverGridGlare& grid,
                                                                 const LuminaireFactors& factors);

/// ResultsGlare::points.
std::size_t observer_grid_points(const ObserverGridGeometry& geometry);

/// ResultsGlare::observer: the observer's luminaires in the results as one eye's glare terms,
/// dimmed, rated by the statistics step traced runs use (eye_glare).
ObserverGlare dimmed_observer_glare(const ObserverGlare& glare, const LuminaireFactors& factors,
                                    const std::string& name, const Estimate& indirect,
                                    const std::string& source, const std::string& field);

}  // namespace lightsolver::detail
