#pragma once
// next_event "auto", per target (docs/statistics.md, "When shadow rays pay"): a surface target's
// or a grid's direct light comes from shadow rays only where their interval is expected to be no
// wider than the photons' would be; elsewhere the target is given back to the photons
// (PreparedMesh/PreparedGrid::direct_by_photons): its direct parts are zero, no shadow ray is
// traced for it, and the next-event groups' bounce-0 photons deposit there.
#include <cstdint>
#include <string>
#include <vector>

#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

/// The seed of the judging parts: independent of the run's own points (PathRng streams keyed by
/// the seed), so that the choice, made from them, does not bias the parts the run keeps.
std::uint64_t judging_seed(std::uint64_t seed);

/// One target's direct light's standard deviations summed over its bins (a surface target's
/// one, a grid's cells: their mean interval width, what a grid's cells show; a sum of variances
/// would let a few shadow-edge cells outvote the rest): by the planned shadow rays and by the
/// photons.
struct DirectWidths {
  double shadow_rays = 0.0;
  double photons = 0.0;
};

/// `parts`: every target's direct parts at the default strata (direct_parts at scale 1, no target
/// given back), from judging_seed(). `photons`: the run's planned photons; `strata_scale`: the
/// scale its shadow rays are planned at. Per bin, shadow rays: the parts' variance / scale^2
/// (stratified sampling does at least that well); photons: binomial, N_g photons of group g
/// carrying flux_g / N_g each, flux_g E (1 - p) / (N_g A) for a bin of area A, p = E A / flux_g.
DirectWidths direct_widths(const PreparedScene& s, const std::vector<DirectPart>& parts,
                           std::uint64_t photons, std::uint32_t strata_scale,
                           const PreparedTarget& target);

/// Sets direct_by_photons on every surface target's meshes and grid whose shadow rays would be
/// wider (direct_widths: ties keep them) and returns the choice in words, each target named
/// by `names` (Scene::targets' names, in PreparedScene::targets' order): "shadow rays: desk;
/// photons: floor (shadow rays would be 3.1x wider)". Empty when every target keeps them.
std::string choose_direct_targets(PreparedScene& s, const std::vector<DirectPart>& parts,
                                  std::uint64_t photons, std::uint32_t strata_scale,
                                  const std::vector<std::string>& names);

/// Gives every target its shadow rays again (direct_by_photons false).
void clear_direct_by_photons(PreparedScene& s);

/// Whether any target's direct light is left to the photons (direct_by_photons).
bool any_target_by_photons(const PreparedScene& s);

/// Whether any target gets its direct light by shadow rays (some grid or surface target without
/// direct_by_photons).
bool any_target_by_shadow_rays(const PreparedScene& s);

/// The photons an accuracy goal is predicted to need for the direct light alone, were it left to
/// the photons: the largest over the goal's bins (whole targets, or cells when `per_cell`) of
/// z^2 u / (goal E)^2, u the bin's photon variance at one photon (direct_widths' photon
/// variance x N). At most `budget`; at least 1.
std::uint64_t goal_photons(const PreparedScene& s, const std::vector<DirectPart>& parts,
                           double goal, double z, bool per_cell, std::uint64_t budget);

/// The scene's direct_by_photons flags, targets in order (meshes, then grids): a run's tallies
/// are only continued (refine) with the same.
std::vector<bool> direct_by_photons_flags(const PreparedScene& s);

}  // namespace lightsolver::detail
