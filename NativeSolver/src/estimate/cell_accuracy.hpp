// The per-cell accuracy rule on a run's tallies (the stopping rule of `--accuracy X --per-cell`).
#pragma once

#include <cstdint>

#include "model/backend.hpp"
#include "model/prepared_scene.hpp"
#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

// Largest relative half-width over every grid cell and every surface target, by the per-cell
// rule (lightsolver/accuracy.hpp: cells darker than 1 % of their grid's mean are judged against
// that 1 %). Infinity while a grid or surface target has no hit.
double worst_cell_relative_half_width(const Scene& scene, const PreparedScene& s,
                                      const TallyBlock& t, std::uint64_t photons,
                                      double confidence);

}  // namespace lightsolver::detail
