#include "core/target_results.hpp"

#include <algorithm>

#include "core/target_types.hpp"

namespace lightsolver::detail {
namespace {

std::uint32_t bin_count(const TargetResult& r) { return r.is_grid ? 1 + r.nu * r.nv : 1; }

// Point k of an observer grid tallies into bin + 2k (prepare_observer_grid's layout): each
// group's part at the maximum's point, and every point's tallies for a rescale.
void add_observer_grid_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                                     const GroupedTallies& tallies, std::uint32_t bin, double z,
                                     const std::vector<std::string>& group_names) {
  const auto points = static_cast<std::uint32_t>(r.observer_grid->points.size());
  const std::uint32_t at =
      bin + 2 * static_cast<std::uint32_t>(r.observer_grid->max_at.value_or(0));
  for (std::size_t g = 0; g < group_names.size(); ++g) {
    Contribution c;
    c.group = group_names[g];
    c.estimate = tallies.group_estimate_z(g, at, bins[at].area_m2, z);
    for (std::uint32_t k = 0; k < points; ++k) c.tallies.push_back(tallies.tally(g, bin + 2 * k));
    r.contributions.push_back(std::move(c));
  }
}

}  // namespace

TargetResult make_target(const Target& t, const std::vector<BinInfo>& bins,
                         const GroupedTallies& tallies, std::uint32_t bin, double confidence,
                         bool judged, const std::vector<Luminaire>* luminaires,
                         const ObserverGridGeometry* observer_grid) {
  const TargetType& row = target_type(t.type);
  const TargetTallies at{t, bins, tallies, bin, confidence, judged, luminaires, observer_grid};
  TargetResult r;
  r.name = t.name;
  r.type = row.name;
  r.requirements = t.requirements;
  r.area_m2 = bins[bin].area_m2;
  r.estimate = at.estimate(bin);
  row.result(at, r);
  return r;
}

void add_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                       const GroupedTallies& tallies, std::uint32_t bin, double confidence,
                       const std::vector<std::string>& group_names) {
  const double z = z_for_confidence(confidence);
  const std::uint32_t n = bin_count(r);
  r.contributions.clear();
  if (r.observer_grid) {
    add_observer_grid_contributions(r, bins, tallies, bin, z, group_names);
    return;
  }
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
