#pragma once
// What rescale (rescale.cpp) asks of glare: an observer's and an observer grid's glare, read back
// from results (results_from_json), dimmed and rated again. Glare sits above core
// (docs/solver.md, "Layers"), so core never includes it: it calls these hooks, which the type
// table (src/tables/target_table.cpp) fills from src/glare (glare_results_io.hpp), as
// backend_list.cpp does for the backends.
#include <cstddef>
#include <map>
#include <memory>
#include <string>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

struct ObserverGridGeometry;  // glare's (glare/observer_grid.hpp); core only passes it on

/// Each luminaire's dimming factor by name (its group's); a name not listed keeps 1.
using LuminaireFactors = std::map<std::string, double>;

struct ResultsGlare {
  /// An observer grid of the results: its positions, view directions and every point's glare
  /// terms, each luminance dimmed by its luminaire's factor.
  std::shared_ptr<const ObserverGridGeometry> (*observer_grid)(const ObserverGridGlare& grid,
                                                               const LuminaireFactors& factors);
  /// Its points (positions x view directions), two tally bins each.
  std::size_t (*points)(const ObserverGridGeometry& geometry);
  /// A plain observer's glare from its luminaires in the results (`glare`), dimmed, for target
  /// `name` at `indirect`: its rebuilt estimate of the indirect illuminance at the eye (lux).
  /// InputError
  /// (`source`, `field`.luminaires[k]...) for a counted luminaire's L, omega or p that is not > 0.
  ObserverGlare (*observer)(const ObserverGlare& glare, const LuminaireFactors& factors,
                            const std::string& name, const Estimate& indirect,
                            const std::string& source, const std::string& field);
};

/// The hooks (defined with the type table, above core and glare).
const ResultsGlare& results_glare();

}  // namespace lightsolver::detail
