#pragma once
// What a daylight-factor grid reads of the scene's sky (docs/daylight.md, "Daylight factor and
// EN 17037"): which luminaire is the sky, and its outside illuminance. In the types layer so
// that the scene's checks and the estimate layer share them without including the daylight
// module's headers (docs/solver.md, "Layers").
#include <cstddef>
#include <optional>

#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

/// The index of the scene's sky luminaire when it has exactly one, else empty.
std::optional<std::size_t> daylight_factor_sky(const Scene& s);

/// A validated sky luminaire's E_out: its model's unobstructed horizontal illuminance above the
/// horizon (no ground, glazing or portals), exact; 0 for a luminaire without a sky model.
double sky_outside_illuminance_lx(const Luminaire& l);

}  // namespace lightsolver::detail
