#pragma once
// Connected reflected light at grids (docs/statistics.md, "Connected reflected light"): with
// next-event estimation a grid's direct light is free of photon noise and what is left is the
// reflected light, which a photon pays for by crossing a cell (one cell in hundreds). Here an
// independent stream of M photons per group is traced through its diffuse reflections, and
// every vertex x is connected to one uniform point y in every cell of every grid (not
// observers) by a shadow ray, depositing Φ_group ρ/π cosθx cosθy / |x − y|² on y's cell, only
// for |x − y| >= the grid's r0; the group's photons count a reflected crossing only closer
// than r0 to its origin (cross_grids). Every (vertex, grid point) pair is counted by exactly one
// of the two, so the sum is unbiased, and the connection's kernel stays below 1/(π r0²) (without
// the partition a wall vertex just above the plane gives infinite variance). Each path's
// deposits on a cell are i.i.d. over the M paths: the cell's part is their mean, its variance the
// sample variance over M. The part is linear in the group's flux and independent of its photons
// and of its next-event points, so it is added into the group's direct parts (DirectPart): every
// recombination (rescale, groups, replicates, the optimizer's combine) stays exact.
#include <cstdint>
#include <string>
#include <vector>

#include "model/backend.hpp"
#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

/// r0 of a grid in cell sizes (the longer cell edge), measured on the box room
/// (docs/BENCHMARKS.md, "Connected reflected light").
inline constexpr double kConnectR0Cells = 2.0;

/// Sets each group's `connect` and each grid's connect_r0 for `mode` ("auto", "on", "off"),
/// after plan_next_event(); `s.connect_off` says why no group has it. Planned for the groups
/// with next_event when the scene has a grid, light is reflected, every material a photon can
/// hit is diffuse (the connection knows the diffuse lobe only) and the backend traces path
/// vertices; `auto` leaves out a run with an accuracy goal or decide (`goal_run`: its photon
/// count is a budget, not what it traces) and a run of `photons` too few for the fewest paths
/// (more than 4 x kConnectRaysPerPhoton shadow rays per photon). `on` refuses (InputError
/// naming connect_reflections) where no group can have it.
void plan_connection(PreparedScene& s, const Backend& backend, const std::string& mode,
                     bool goal_run, std::uint64_t photons);

/// Shadow rays per photon of the run the connections are sized to (docs/BENCHMARKS.md,
/// "Connected reflected light").
inline constexpr double kConnectRaysPerPhoton = 6.0;

/// The paths per connected group for a run of `photons` photons: about kConnectRaysPerPhoton
/// shadow rays per photon, counting two vertices per path and one ray per cell, at least 512;
/// 16384 for a `goal_run`. 0 when no group is connected.
std::uint64_t connection_paths(const PreparedScene& s, std::uint64_t photons, bool goal_run);

/// Adds each connected group's connected reflected light at every grid (its cells and the
/// whole grid) into `direct` (groups x bins, as direct_parts() lays it out), from `paths`
/// photons of the group's own stream with `seed`.
void add_connected_reflection(const PreparedScene& s, Backend& backend, std::uint64_t seed,
                              std::uint64_t paths, std::vector<DirectPart>& direct);

}  // namespace lightsolver::detail
