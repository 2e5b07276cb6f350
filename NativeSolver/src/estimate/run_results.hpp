#pragma once
// A run's results from its grouped tallies: every target, every group, the warnings every run
// carries. Shared by Simulation::run (one trace of all groups) and Simulation::combine (groups
// traced apart, the optimizer's reuse).
#include <cstdint>
#include <vector>

#include "model/backend.hpp"
#include "model/groups.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// Every target of the scene from the grouped tallies (grouped once): the type's own part from
/// its row (target_results.cpp, target_types.cpp), and each group's part when asked for.
/// `luminaires`: those observers rate for glare (null: the scene's; Simulation::combine passes
/// them at the fluxes it combines).
std::vector<TargetResult> all_targets(const Scene& scene, const PreparedScene& s,
                                      const GroupedTallies& tallies, double confidence, bool judged,
                                      bool contributions,
                                      const std::vector<Luminaire>* luminaires = nullptr);

/// The same after a run's first `photons` photons, shared out by the groups' photon shares.
std::vector<TargetResult> all_targets(const Scene& scene, const PreparedScene& s,
                                      const TallyBlock& t, std::uint64_t photons, double confidence,
                                      bool judged, bool contributions);

/// Every group: its name, flux, photons traced (`photons[g]`) and luminaires.
std::vector<GroupResult> group_results(const Scene& scene, const PreparedScene& s,
                                       const std::vector<std::uint64_t>& photons);

/// Every luminaire as traced, in scene order (the one place the results' per-luminaire flux
/// comes from): its flux, TILT factor and emitted flux as prepare_luminaires() sums them into
/// its group's flux, times `dimming[g]` for group g (empty: 1, a traced run).
std::vector<LuminaireResult> luminaire_results(const Scene& scene, const PreparedScene& s,
                                               const std::vector<double>& dimming = {});

/// The scene's and the photometric files' warnings, and those the run's counts call for (zero
/// flux, capped or cut paths, partial, undecided, accuracy budget spent).
void add_warnings(const Scene& scene, Results& r);

}  // namespace lightsolver::detail
