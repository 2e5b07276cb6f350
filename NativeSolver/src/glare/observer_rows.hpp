#pragma once
// The glare of the observer and observer-grid target types: their rows' result hooks
// (types/target_types.hpp). Core defines the rest of those rows and never includes glare; the
// type table (src/tables/target_table.cpp) puts these hooks into them.
#include "types/target_types.hpp"

namespace lightsolver::detail {

/// An observer's result: its eye's glare from the scene's luminaires (none when the results
/// are rebuilt without the scene: rescale rates a plain observer itself).
void observer_result(const TargetTallies& tallies, TargetResult& r);

/// An observer grid's result: every point's glare and their maximum, its estimate that of the
/// maximum's point. The geometry comes from the scene's luminaires (traced) or from the
/// results (rescale, dimmed).
void observer_grid_result(const TargetTallies& tallies, TargetResult& r);

}  // namespace lightsolver::detail
