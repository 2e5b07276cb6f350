#include "model/groups.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/replicates.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver::detail {

void set_photon_shares(std::vector<PreparedGroup>& groups, const std::vector<double>& weights) {
  auto weight = [&](std::size_t g) { return weights.empty() ? groups[g].flux_lm : weights[g]; };
  double lit = 0.0, total = 0.0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (weight(g) > 0.0) {
      lit += 1.0;
      total += weight(g);
    }
  }
  double sum = 0.0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    groups[g].share = weight(g) > 0.0 ? std::max(weight(g) / total, kGroupFloor / lit) : 0.0;
    sum += groups[g].share;
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    // One lit group: exactly 1, so its photons are the run's (ungrouped results unchanged).
    groups[g].share = lit == 1.0 ? (weight(g) > 0.0 ? 1.0 : 0.0) : groups[g].share / sum;
  }
}

namespace {

// Shares out the m photons of groups [lo, hi) (`prefix`: cumulative shares).
void split(const std::vector<double>& prefix, std::size_t lo, std::size_t hi, std::uint64_t m,
           std::vector<std::uint64_t>& out) {
  if (hi - lo == 1) {
    out[lo] = m;
    return;
  }
  const std::size_t mid = lo + (hi - lo) / 2;
  const double all = prefix[hi] - prefix[lo], first = prefix[mid] - prefix[lo];
  // floor(m a + 1/2) grows by 0 or 1 when m grows by 1 (0 <= a <= 1), and so does the rest.
  const double a = all > 0.0 ? std::clamp(first / all, 0.0, 1.0) : 0.5;
  const auto left = std::min(m, static_cast<std::uint64_t>(std::floor(double(m) * a + 0.5)));
  split(prefix, lo, mid, left, out);
  split(prefix, mid, hi, m - left, out);
}

}  // namespace

std::vector<std::uint64_t> group_photons(const std::vector<PreparedGroup>& groups,
                                         std::uint64_t n) {
  std::vector<std::uint64_t> out(groups.size(), 0);
  if (groups.empty()) return out;
  std::vector<double> prefix{0.0};
  for (const PreparedGroup& g : groups) prefix.push_back(prefix.back() + g.share);
  split(prefix, 0, groups.size(), n, out);
  return out;
}

std::vector<GroupRange> group_ranges(const std::vector<PreparedGroup>& groups, std::uint64_t first,
                                     std::uint64_t count) {
  std::vector<GroupRange> ranges;
  const auto before = group_photons(groups, first), after = group_photons(groups, first + count);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (after[g] > before[g]) {
      ranges.push_back({static_cast<std::uint32_t>(g), before[g], after[g] - before[g]});
    }
  }
  return ranges;
}

void check_group_tallies(const std::string& file, std::size_t groups, std::size_t bins) {
  const double tallies = double(groups) * double(bins);
  if (tallies > double(kMaxGroupTallies)) {
    throw InputError(file, "luminaires[].group",
                     std::to_string(groups) + " luminaire groups x " + std::to_string(bins) +
                         " target bins = " + std::to_string(std::uint64_t(tallies)) +
                         " tallies, more than the limit 2^26 (1 GiB): give luminaires a shared "
                         "`group`, or use fewer grid cells");
  }
}

Estimate GroupedTallies::group_estimate_z(std::size_t group, std::uint32_t bin, double area_m2,
                                          double z) const {
  if (replicates > 1) return replicate_estimate(*this, group, bin, area_m2, z);
  const bool direct_part = has_direct_part(group);
  // A next-event group's photons in a scene where nothing reflects deposit nothing, exactly.
  Estimate e = direct_part && !photons_reflect
                   ? Estimate{}
                   : make_estimate_z(tally(group, bin), photons[group], flux_lm[group] / area_m2, z);
  if (!direct_part) return e;
  const DirectPart& d = (*direct)[group * bin_count + bin];
  return with_direct_part(e, d.lux * direct_scale[group],
                          d.variance * direct_scale[group] * direct_scale[group], d.lit, z);
}

Estimate GroupedTallies::estimate_z(std::uint32_t bin, double area_m2, double z) const {
  if (replicates > 1) return replicate_estimate(*this, std::nullopt, bin, area_m2, z);
  std::size_t lit = 0, last = 0;
  for (std::size_t g = 0; g < photons.size(); ++g) {
    if (photons[g] > 0 && flux_lm[g] > 0.0) {
      ++lit;
      last = g;
    }
  }
  if (lit == 1) return group_estimate_z(last, bin, area_m2, z);
  Estimate e;
  if (lit == 0) return e;  // no light: exactly zero
  double variance = 0.0, below = 0.0, above = 0.0;
  for (std::size_t g = 0; g < photons.size(); ++g) {
    if (!(photons[g] > 0 && flux_lm[g] > 0.0)) continue;
    const Estimate part = group_estimate_z(g, bin, area_m2, z);
    e.mean += part.mean;
    e.hits += part.hits;
    variance += part.sigma * part.sigma;
    below += (part.mean - part.ci_low) * (part.mean - part.ci_low);
    above += (part.ci_high - part.mean) * (part.ci_high - part.mean);
  }
  e.sigma = std::sqrt(variance);
  e.ci_low = std::clamp(e.mean - std::sqrt(below), 0.0, e.mean);
  e.ci_high = std::max(e.mean + std::sqrt(above), e.mean);
  if (!(std::isfinite(e.mean) && std::isfinite(e.ci_high) && std::isfinite(e.sigma))) {
    throw std::overflow_error("combined estimate: non-finite value");
  }
  return e;
}

Estimate GroupedTallies::estimate(std::uint32_t bin, double area_m2, double confidence) const {
  thread_local double cached_confidence = -1.0, z = 0.0;
  if (confidence != cached_confidence) {
    z = z_for_confidence(confidence);
    cached_confidence = confidence;
  }
  return estimate_z(bin, area_m2, z);
}

GroupedTallies grouped_tallies(const PreparedScene& s, const std::vector<Tally>& bins,
                               std::uint64_t photons) {
  GroupedTallies t;
  t.bins = &bins;
  t.bin_count = s.bins.size();
  const std::size_t block = s.groups.size() * s.bins.size();
  t.replicates = block > 0 && bins.size() > block ? bins.size() / block : 1;
  t.photons = group_photons(s.groups, photons / t.replicates);
  for (std::uint64_t& n : t.photons) n *= t.replicates;
  for (const PreparedGroup& g : s.groups) t.flux_lm.push_back(g.flux_lm);
  if (!s.direct.empty()) {
    t.direct = &s.direct;
    for (const PreparedGroup& g : s.groups) {
      t.next_event.push_back(g.next_event ? 1 : 0);
      t.direct_scale.push_back(1.0);
    }
    t.photons_reflect = s.photons_reflect;
  }
  return t;
}

Estimate with_direct_part(const Estimate& photons, double lux, double variance, std::uint64_t lit,
                          double z) {
  Estimate e = photons;
  // The direct mean is a sum over its points (and a grid's cells) in double: its rounding, below
  // (terms + a few) x 2^-52 of it (Higham's bound for recursive summation of non-negative terms,
  // each computed to a few ulps), belongs in the interval. A field known exactly (a beam filling
  // a cell: every sample equal, variance 0) then still holds its exact value.
  const double rounding = (double(lit) + 16.0) * std::numeric_limits<double>::epsilon() * lux;
  const double half = z * std::sqrt(variance) + rounding;
  e.mean = photons.mean + lux;
  e.sigma = std::hypot(photons.sigma, std::sqrt(variance));
  e.hits = photons.hits + lit;
  e.ci_low = std::clamp(e.mean - std::hypot(photons.mean - photons.ci_low, half), 0.0, e.mean);
  e.ci_high = std::max(e.mean + std::hypot(photons.ci_high - photons.mean, half), e.mean);
  if (!(std::isfinite(e.mean) && std::isfinite(e.ci_high) && std::isfinite(e.sigma))) {
    throw std::overflow_error("next-event estimate: non-finite value");
  }
  return e;
}

}  // namespace lightsolver::detail
