#pragma once
// What rescale (rescale.cpp) asks of glare: an observer's and an observer grid's glare read back
// from a results document and dimmed. Glare sits above core (docs/solver.md, "Layers"), so core
// never includes it: it calls these hooks, which the type table (src/tables/target_table.cpp)
// fills from src/glare (glare_results_io.hpp), as backend_list.cpp does for the backends.
#include <cstddef>
#include <map>
#include <memory>
#include <string>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

class JsonNode;
struct ObserverGridGeometry;  // glare's (glare/observer_grid.hpp); core only passes it on

/// Each luminaire's dimming factor by name (its group's); a name not listed keeps 1.
using LuminaireFactors = std::map<std::string, double>;

struct ResultsGlare {
  /// Observer grid `target` of a results document: its positions, view directions and every
  /// point's glare terms, each luminance dimmed by its luminaire's factor. InputError naming
  /// the field when any is missing, short or out of range.
  std::shared_ptr<const ObserverGridGeometry> (*observer_grid)(const JsonNode& target,
                                                               const LuminaireFactors& factors);
  /// Its points (positions x view directions), two tally bins each.
  std::size_t (*points)(const ObserverGridGeometry& geometry);
  /// Observer `target`'s glare from its luminaires in the results, dimmed, at `indirect`: its
  /// rebuilt estimate of the indirect illuminance at the eye (lux).
  ObserverGlare (*observer)(const JsonNode& target, const LuminaireFactors& factors,
                            const std::string& name, const Estimate& indirect);
};

/// The hooks (defined with the type table, above core and glare).
const ResultsGlare& results_glare();

}  // namespace lightsolver::detail
