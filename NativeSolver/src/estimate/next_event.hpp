#pragma once
// Next-event estimation of direct light at targets (docs/statistics.md, "Next-event
// estimation"): the illuminance that reaches a grid cell or a surface target straight from a
// luminaire is estimated by shadow rays from stratified points on the receiver to the
// luminaires (their types' `direct` hooks), and only the light after at least one scattering
// by photons (PreparedGroup::next_event). Each (group, bin) gets its own points, two per
// stratum: the stratified mean is unbiased and so is its variance estimate, and the groups'
// parts stay independent of each other and of every photon stream.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/backend.hpp"
#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

/// Strata per side of a grid cell (s x s strata, two points each): 4 gives 32 points per cell.
inline constexpr std::uint32_t kCellStrataSide = 4;
/// Strata of a surface target's area (two points each).
inline constexpr std::uint32_t kSurfaceStrata = 256;

/// Sets every group's next_event flag for `mode` ("auto", "on", "off") and the scene's reason
/// when none has it; clears `s.direct` and gives every target its shadow rays again
/// (direct_by_photons false: auto's choice is made per run, estimate/direct_choice.hpp). auto and
/// on give it to every group whose luminaires all have a direct hook, when the scene has a grid or
/// surface target and the backend traces shadow rays; `on` refuses (InputError naming next_event)
/// where no group can have it.
void plan_next_event(PreparedScene& s, const Backend& backend, const std::string& mode);

/// Shadow rays direct_parts() traces at most with `strata_scale` (every point to every luminaire
/// of the planned groups; none for targets given back to the photons, direct_by_photons).
std::uint64_t direct_ray_count(const PreparedScene& s, std::uint32_t strata_scale);

/// The direct parts (PreparedScene::direct) of the groups planned, for every grid (not the
/// indirect-only ones), its cells and every surface target, with the points drawn from `seed`
/// (zero, untraced, at targets given back to the photons: direct_by_photons);
/// `strata_scale` multiplies the strata per side (1: the defaults above). Empty when no group
/// has next_event.
std::vector<DirectPart> direct_parts(const PreparedScene& s, Backend& backend, std::uint64_t seed,
                                     std::uint32_t strata_scale = 1);

/// direct_parts(), asking `stop` before each batch of shadow rays (about 2^18 rays): nullopt
/// once it says true (what was traced is dropped: a part is whole or absent).
std::optional<std::vector<DirectPart>> direct_parts_unless(const PreparedScene& s, Backend& backend,
                                                           std::uint64_t seed,
                                                           std::uint32_t strata_scale,
                                                           const std::function<bool()>& stop);

}  // namespace lightsolver::detail
