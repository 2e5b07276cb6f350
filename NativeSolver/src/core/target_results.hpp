#pragma once
// A target's results (estimate, cells, Emin/Emax/U0 and their intervals, per-group
// contributions) from grouped tallies. Shared by runs (simulation.cpp) and `rescale`
// (rescale.cpp), so a rescaled result is built by the same code as a traced one.
#include <cstdint>
#include <string>
#include <vector>

#include "core/groups.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

struct ObserverGridGeometry;

/// The target `t` whose first bin is `bin` (`bins`: every bin's area): the common fields here,
/// the type's own in its row (target_types.cpp). `luminaires`: the scene's, for glare; null
/// when rebuilt without the scene (rescale: observers then get no glare here, observer grids
/// theirs from `observer_grid`, the geometry read back from the results).
TargetResult make_target(const Target& t, const std::vector<BinInfo>& bins,
                         const GroupedTallies& tallies, std::uint32_t bin, double confidence,
                         bool judged, const std::vector<Luminaire>* luminaires,
                         const ObserverGridGeometry* observer_grid = nullptr);

/// Adds each group's part of the target (its estimate, its cells, its tallies), in group order.
/// An observer grid's part is that of the point of its maximum (point 0 without glare), its
/// tallies every point's (the bin at bin + 2k).
void add_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                       const GroupedTallies& tallies, std::uint32_t bin, double confidence,
                       const std::vector<std::string>& group_names);

}  // namespace lightsolver::detail
