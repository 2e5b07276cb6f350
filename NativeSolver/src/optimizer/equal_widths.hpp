#pragma once
// Photon counts for equal interval widths under next-event estimation (docs/optimization.md §6,
// "Equal widths"): the direct light at the targets from shadow rays removes part of the
// photons' variance, so fewer photons give the intervals a photon-only search has at N.
#include <cstdint>

#include "lightsolver/optimizer/scene_problem.hpp"

namespace lightsolver::optimizer {

/// The objective's variance with `with`'s next-event setting over that of photons alone
/// (next_event "off"; a second evaluator built like `with` from `overrides`), both traced at
/// `cells` with `photons` and the same seed, clamped to (0, 1]: 1 where `with` had no direct
/// part (nothing to gain) or the photon-only variance is 0. Never more photons than asked.
double width_factor(const SceneProblem& problem, SceneEvaluator& with,
                    const RunOverrides& overrides, const VnsOptions& search, std::uint64_t photons,
                    const Configuration& cells);

/// `photons` scaled by `factor` (rounded, at least 1), as the search scales them.
std::uint64_t scaled_photons(std::uint64_t photons, double factor);

}  // namespace lightsolver::optimizer
