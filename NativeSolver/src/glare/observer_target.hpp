#pragma once
// Glue between the traced scene and the UGR of docs/glare.md: the scene's luminaires as glare
// sources, and an observer target's glare from its traced indirect illuminance.
#include <vector>

#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

// The glare of observer `t` (scene target of type Observer) for `luminaires`, from `indirect`:
// the target's estimate of the indirect illuminance at the eye (lux). L_b = E / pi; UGR at L_b,
// and at its interval's ends (UGR falls as L_b rises). Point, spot and directional luminaires
// and photometric files without a luminous area are listed as not counted, with the reason.
ObserverGlare observer_glare(const Target& t, const std::vector<Luminaire>& luminaires,
                             const Estimate& indirect);

}  // namespace lightsolver::detail
