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
#include <functional>
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
/// vertices; `auto` leaves out a plain run (not `goal_run`, an accuracy goal or decide, whose
/// photon count is a budget) of `photons` too few for the fewest paths (more than
/// 4 x kConnectRaysPerPhoton shadow rays per photon). `on` refuses (InputError naming
/// connect_reflections) where no group can have it.
void plan_connection(PreparedScene& s, const Backend& backend, const std::string& mode,
                     bool goal_run, std::uint64_t photons);

/// Leaves every group and grid unconnected, `why` in `s.connect_off` (a run stopped before its
/// connection, or one `auto` judged not to pay): the photons count every reflected crossing.
void drop_connection(PreparedScene& s, const std::string& why);

/// Fewest paths per connected group: the sample variance over them is the part's interval. A
/// plain run traces these before its photons (whole if it is stopped during them), and `auto`
/// judges from them whether the connection pays (connection_pays).
inline constexpr std::uint64_t kConnectMinPaths = 512;

/// Paths per connected group of a run that decides: fixed before the photons (its stopping rules
/// read the parts its results end with), whatever its budget.
inline constexpr std::uint64_t kConnectDecidePaths = 16384;

/// Most paths per connected group an accuracy goal refines to (doubling from kConnectMinPaths).
inline constexpr std::uint64_t kConnectMaxGoalPaths = std::uint64_t(1) << 17;

/// `auto` keeps the connection only where the connected light at the grids (the whole grids'
/// parts, over the connected groups) is at least this share of their direct light: below it the
/// photons' far reflected crossings are too few to be worth the shadow rays.
inline constexpr double kConnectMinShare = 0.02;

/// Whether the connected parts `connected` (groups x bins, add_connected_reflection) pay beside
/// the direct parts `direct`: their light at the grids is at least kConnectMinShare of the direct
/// light there. Otherwise false, with the shares in `why`.
bool connection_pays(const PreparedScene& s, const std::vector<DirectPart>& direct,
                     const std::vector<DirectPart>& connected, std::string& why);

/// Shadow rays per photon of the run the connections are sized to (docs/BENCHMARKS.md,
/// "Connected reflected light").
inline constexpr double kConnectRaysPerPhoton = 6.0;

/// Most paths of a plain run per photon: each path is traced as a photon is.
inline constexpr double kConnectMaxPathShare = 0.25;

/// The paths per connected group for a plain run of `photons` photons: about
/// kConnectRaysPerPhoton shadow rays per photon, counting two vertices per path and one ray per
/// cell, at most kConnectMaxPathShare x `photons`, at least kConnectMinPaths. 0 when no group is
/// connected.
std::uint64_t connection_paths(const PreparedScene& s, std::uint64_t photons);

/// Adds each connected group's connected reflected light at every grid (its cells and the
/// whole grid) into `direct` (groups x bins, as direct_parts() lays it out), from `paths`
/// photons of the group's own stream with `seed`, asking `stop` (may be empty) before each batch
/// of about 2^18 shadow rays. Stopped: false, and `direct` is as it was (a part is whole or
/// absent). The paths are the same whatever the batches: the result depends on `seed` and
/// `paths` only.
bool add_connected_reflection(const PreparedScene& s, Backend& backend, std::uint64_t seed,
                              std::uint64_t paths, std::vector<DirectPart>& direct,
                              const std::function<bool()>& stop = {});

}  // namespace lightsolver::detail
