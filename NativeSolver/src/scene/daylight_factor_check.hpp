#pragma once
// Daylight-factor grids in a scene (docs/scene-format.md, "Targets"; docs/daylight.md,
// "Daylight factor and EN 17037"): which sky they read, and the checks of their keys.
#include <cstddef>
#include <optional>

#include "lightsolver/scene.hpp"
#include "types/sky_daylight.hpp"  // daylight_factor_sky

namespace lightsolver::detail {

/// Checks target `i`'s daylight-factor keys: on a daylight-factor grid, exactly one sky whose
/// group holds nothing else, a positive outside illuminance, no illuminance requirement, DF
/// requirements in range (an EN 17037 level with its median); on any other target, no DF key.
/// Throws InputError naming the field (targets[i].quantity, targets[i].requirements.KEY,
/// luminaires[j].group).
void check_daylight_factor(const Scene& s, std::size_t i);

}  // namespace lightsolver::detail
