#pragma once
// A target's results (estimate, cells, Emin/Emax/U0 and their intervals, per-group
// contributions) from grouped tallies. Shared by runs (simulation.cpp) and `rescale`
// (rescale.cpp), so a rescaled result is built by the same code as a traced one. Where each
// tally is comes from the target's PreparedTarget record (prepared_scene.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "model/groups.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

struct ObserverGridGeometry;
struct DaylightFactorBasis;

/// The target `t` whose bins `layout` gives (`bins`: every bin's area): the common fields here,
/// the type's own in its row (target_types.cpp). `luminaires`: the scene's, for glare; null
/// when rebuilt without the scene (rescale: observers then get no glare here, observer grids
/// theirs from `observer_grid`, the geometry read back from the results). `daylight`: the sky a
/// daylight-factor grid reads (null: none reported).
TargetResult make_target(const Target& t, const std::vector<BinInfo>& bins,
                         const GroupedTallies& tallies, const PreparedTarget& layout,
                         double confidence, bool judged, const std::vector<Luminaire>* luminaires,
                         const ObserverGridGeometry* observer_grid = nullptr,
                         const DaylightFactorBasis* daylight = nullptr);

/// Adds each group's part of the target (its estimate, its cells, its tallies), in group order.
/// A target with eyes gives the part of the eye of its maximum (eye 0 without glare) and every
/// eye's tallies; any other its whole bin's and its cells'.
void add_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                       const GroupedTallies& tallies, const PreparedTarget& layout,
                       double confidence, const std::vector<std::string>& group_names);

}  // namespace lightsolver::detail
