#include "core/target_results.hpp"

#include <algorithm>

namespace lightsolver::detail {
namespace {

// Cell and grid estimates at any alpha, for the simultaneous intervals of grid_intervals();
// z is computed once per alpha (the cells share it).
GridSampler grid_sampler(const Target& t, const std::vector<BinInfo>& bins,
                         const GroupedTallies& tallies, std::uint32_t bin) {
  auto estimate = [&bins, &tallies, bin, alpha = -1.0, z = 0.0](std::uint32_t b, double a) mutable {
    if (a != alpha) z = z_for_alpha(alpha = a);
    return tallies.estimate_z(bin + b, bins[bin + b].area_m2, z);
  };
  return {t.nu * t.nv, [estimate](double a) mutable { return estimate(0, a); },
          [estimate](std::uint32_t c, double a) mutable { return estimate(1 + c, a); }};
}

std::uint32_t bin_count(const TargetResult& r) { return r.is_grid ? 1 + r.nu * r.nv : 1; }

}  // namespace

TargetResult make_target(const Target& t, const std::vector<BinInfo>& bins,
                         const GroupedTallies& tallies, std::uint32_t bin, double confidence,
                         bool judged) {
  TargetResult r;
  r.name = t.name;
  r.requirements = t.requirements;
  r.is_grid = t.type == Target::Type::Grid;
  r.is_observer = t.type == Target::Type::Observer;
  r.area_m2 = bins[bin].area_m2;
  auto estimate = [&](std::uint32_t b) { return tallies.estimate(b, bins[b].area_m2, confidence); };
  r.estimate = estimate(bin);
  if (!r.is_grid) return r;
  r.nu = t.nu;
  r.nv = t.nv;
  r.cells.reserve(std::size_t(t.nu) * t.nv);
  for (std::uint32_t c = 0; c < t.nu * t.nv; ++c) r.cells.push_back(estimate(bin + 1 + c));
  const auto [lo, hi] = std::minmax_element(r.cells.begin(), r.cells.end(),
                                            [](auto& a, auto& b) { return a.mean < b.mean; });
  r.min_lux = lo->mean;
  r.max_lux = hi->mean;
  r.uniformity = r.estimate.mean > 0.0 ? r.min_lux / r.estimate.mean : 0.0;
  if (judged) {
    r.intervals = grid_intervals(grid_sampler(t, bins, tallies, bin), confidence, r.min_lux,
                                 r.max_lux, r.estimate.mean);
  }
  return r;
}

void add_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                       const GroupedTallies& tallies, std::uint32_t bin, double confidence,
                       const std::vector<std::string>& group_names) {
  const double z = z_for_confidence(confidence);
  const std::uint32_t n = bin_count(r);
  r.contributions.clear();
  for (std::size_t g = 0; g < group_names.size(); ++g) {
    Contribution c;
    c.group = group_names[g];
    c.estimate = tallies.group_estimate_z(g, bin, bins[bin].area_m2, z);
    for (std::uint32_t b = 0; b < n; ++b) c.tallies.push_back(tallies.tally(g, bin + b));
    for (std::uint32_t b = 1; r.is_grid && b < n; ++b) {
      c.cells.push_back(tallies.group_estimate_z(g, bin + b, bins[bin + b].area_m2, z));
    }
    r.contributions.push_back(std::move(c));
  }
}

}  // namespace lightsolver::detail
