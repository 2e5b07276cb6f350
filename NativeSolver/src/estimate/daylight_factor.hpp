#pragma once
// A daylight-factor grid's result from its sky group's tallies (docs/daylight.md, "Daylight
// factor and EN 17037"; docs/statistics.md, "Order statistics of noisy cells").
#include <optional>

#include "types/target_types.hpp"

namespace lightsolver::detail {

/// The daylight factor of the grid `tt` (tt.daylight set): each cell's and the grid's sky
/// estimate at the sky's traced flux over its outside illuminance, in percent, with the
/// smallest cell and the values reached over 50 % and 95 % of the area.
DaylightFactorResult daylight_factor_result(const TargetTallies& tt);

/// The basis of the scene's daylight-factor grids: its one sky, the prepared group that holds
/// it, its flux and outside illuminance; empty when no target is a daylight-factor grid (or the
/// scene has not exactly one sky).
std::optional<DaylightFactorBasis> daylight_factor_basis(const Scene& scene,
                                                         const std::vector<PreparedGroup>& groups);

}  // namespace lightsolver::detail
