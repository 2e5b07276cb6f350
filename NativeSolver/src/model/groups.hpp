#pragma once
// Luminaire groups (docs/statistics.md, "Groups"): each group has its own photon stream and its
// own tallies, so the groups' estimates are independent and a result is their sum,
// E = sum_g s_g E_g with Var = sum_g s_g^2 Var_g, for any dimming factors s_g.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "model/prepared_scene.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver::detail {

/// Each lit group's share is max(flux fraction, kGroupFloor / lit groups), normalised (by a sum
/// of at most 1 + kGroupFloor): so at least kGroupFloor / (1.1 lit groups) of the photons, and
/// the floor costs the brightest groups at most 10 % of theirs.
inline constexpr double kGroupFloor = 0.1;

/// Largest groups x bins of one run: 2^26 tallies, 1 GiB (16 bytes each) per copy.
inline constexpr std::uint64_t kMaxGroupTallies = std::uint64_t(1) << 26;

/// Sets every group's photon share: max(weight fraction, kGroupFloor / weighted groups),
/// normalised; 0 for a group of weight 0. A single weighted group gets exactly 1. The weights are
/// the groups' fluxes, or `weights` (one per group) where given: fixed shares that do not move
/// when a flux does (Simulation::fix_photon_shares, the optimizer's reused traces).
void set_photon_shares(std::vector<PreparedGroup>& groups, const std::vector<double>& weights = {});

/// The photons of every group among a run's first `n`: they add up to exactly n, each is
/// non-decreasing in n (so consecutive batches are consecutive ranges of each group's stream)
/// and within about log2(groups) of n x share. The groups are split in halves recursively, the
/// first half getting floor(m a + 1/2) of the m photons of both, a its share of theirs: each
/// split is exact and monotone, hence so is the whole. One group gets all n.
std::vector<std::uint64_t> group_photons(const std::vector<PreparedGroup>& groups, std::uint64_t n);

/// A run's photons [first, first + count), group by group: photon i of group g is photon i of
/// g's stream whatever the batches.
struct GroupRange {
  std::uint32_t group = 0;
  std::uint64_t first = 0, count = 0;
};
std::vector<GroupRange> group_ranges(const std::vector<PreparedGroup>& groups, std::uint64_t first,
                                     std::uint64_t count);

/// Refuses runs whose groups x bins exceed kMaxGroupTallies (InputError naming `group`).
void check_group_tallies(const std::string& file, std::size_t groups, std::size_t bins);

/// Per-group tallies (group-major: group g's bin b at g * bin_count + b) and what turns them
/// into lux: each group's photons and flux (dimmed, in a rescale).
struct GroupedTallies {
  const std::vector<Tally>* bins = nullptr;
  std::size_t bin_count = 0;
  std::vector<std::uint64_t> photons;  // per group
  std::vector<double> flux_lm;         // per group, times its dimming factor
  // Next-event estimation: each group's direct part per bin (group-major; null: none), per
  // group whether it has one (`next_event`: its photons then tally light after a scattering
  // only) and the factor on it (its flux here over its flux when the parts were computed).
  const std::vector<DirectPart>* direct = nullptr;
  std::vector<std::uint8_t> next_event{};
  std::vector<double> direct_scale{};
  bool photons_reflect = true;  // false: a group with a direct part has no photon part

  bool has_direct_part(std::size_t group) const {
    return direct != nullptr && next_event[group] != 0;
  }
  /// Above 1: a quasi-random run's replicates, `bins` holding one groups x bin_count block
  /// each (replicate r's group g, bin b at (r * groups + g) * bin_count + b), `photons` each
  /// group's photons over all replicates (model/replicates.hpp). tally() reads replicate 0.
  std::size_t replicates = 1;

  const Tally& tally(std::size_t group, std::uint32_t bin) const {
    return (*bins)[group * bin_count + bin];
  }
  /// Group g's part of bin `bin` (area in m2) at critical value z: its photons' estimate, plus
  /// its direct part where it has one (the two independent: the ends' distances add in
  /// quadrature, docs/statistics.md "Next-event estimation").
  Estimate group_estimate_z(std::size_t group, std::uint32_t bin, double area_m2, double z) const;
  /// The sum over the groups: the group's own estimate where one group has light (bit for bit
  /// that of an ungrouped run), else mean = sum of means, and each end of the interval the
  /// root-sum-square of the groups' distances to their own ends (docs/statistics.md).
  Estimate estimate_z(std::uint32_t bin, double area_m2, double z) const;
  Estimate estimate(std::uint32_t bin, double area_m2, double confidence) const;
};

/// `photons` (a group's photon estimate of a bin) plus a direct part of mean `lux` and
/// `variance` from `lit` lit samples, at critical value z: means add, the ends' distances add
/// in quadrature (independent estimates), sigma too; hits count the lit samples as well.
Estimate with_direct_part(const Estimate& photons, double lux, double variance, std::uint64_t lit,
                          double z);

/// The tallies of a run over `bins` (groups x scene bins) after its first `photons` photons;
/// `bins` R times that long: a quasi-random run's R replicates of photons / R each.
GroupedTallies grouped_tallies(const PreparedScene& s, const std::vector<Tally>& bins,
                               std::uint64_t photons);

}  // namespace lightsolver::detail
