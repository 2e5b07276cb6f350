#include "estimate/target_results.hpp"

#include <algorithm>

#include "types/target_types.hpp"

namespace lightsolver::detail {
namespace {

// Group g's part of bin b as a rescale reads it back (model/groups.hpp, group_estimate_z): what
// its photons tallied, and its direct part where next-event estimation gave it one.
Contribution::PhotonLight photon_light(const GroupedTallies& tallies, std::size_t g) {
  if (!tallies.has_direct_part(g)) return Contribution::PhotonLight::All;
  return tallies.photons_reflect ? Contribution::PhotonLight::Reflected
                                 : Contribution::PhotonLight::None;
}

DirectLight direct_light(const GroupedTallies& tallies, std::size_t g, std::uint32_t bin) {
  const DirectPart& d = (*tallies.direct)[g * tallies.bin_count + bin];
  const double f = tallies.direct_scale[g];
  return {d.lux * f, d.variance * f * f, d.lit};
}

// Each group's part at the eye of the maximum, and every eye's tallies for a rescale.
void add_eye_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                           const GroupedTallies& tallies, const PreparedTarget& layout, double z,
                           const std::vector<std::string>& group_names) {
  const std::size_t max_at = r.observer_grid ? r.observer_grid->max_at.value_or(0) : 0;
  const std::uint32_t at = layout.point_bin(static_cast<std::uint32_t>(max_at));
  for (std::size_t g = 0; g < group_names.size(); ++g) {
    Contribution c;
    c.group = group_names[g];
    c.estimate = tallies.group_estimate_z(g, at, bins[at].area_m2, z);
    c.photon_light = photon_light(tallies, g);  // eyes have no direct part
    for (std::uint32_t k = 0; k < layout.points; ++k) {
      c.tallies.push_back(tallies.tally(g, layout.point_bin(k)));
    }
    r.contributions.push_back(std::move(c));
  }
}

}  // namespace

TargetResult make_target(const Target& t, const std::vector<BinInfo>& bins,
                         const GroupedTallies& tallies, const PreparedTarget& layout,
                         double confidence, bool judged, const std::vector<Luminaire>* luminaires,
                         const ObserverGridGeometry* observer_grid,
                         const DaylightFactorBasis* daylight) {
  const TargetType& row = target_type(t.type);
  const TargetTallies at{t,      bins,       tallies,       layout,  confidence,
                         judged, luminaires, observer_grid, daylight};
  TargetResult r;
  r.name = t.name;
  r.type = row.name;
  r.requirements = t.requirements;
  r.area_m2 = bins[layout.bin].area_m2;
  r.estimate = at.estimate(layout.bin);
  row.result(at, r);
  return r;
}

void add_contributions(TargetResult& r, const std::vector<BinInfo>& bins,
                       const GroupedTallies& tallies, const PreparedTarget& layout,
                       double confidence, const std::vector<std::string>& group_names) {
  const double z = z_for_confidence(confidence);
  r.contributions.clear();
  if (layout.points > 0) {
    add_eye_contributions(r, bins, tallies, layout, z, group_names);
    return;
  }
  const std::uint32_t bin = layout.bin;
  for (std::size_t g = 0; g < group_names.size(); ++g) {
    Contribution c;
    c.group = group_names[g];
    c.estimate = tallies.group_estimate_z(g, bin, bins[bin].area_m2, z);
    c.tallies.push_back(tallies.tally(g, bin));
    c.photon_light = photon_light(tallies, g);
    const bool direct = tallies.has_direct_part(g);
    if (direct) c.direct.push_back(direct_light(tallies, g, bin));
    for (std::uint32_t k = 0; k < layout.cells; ++k) {
      const std::uint32_t b = layout.cell_bin(k);
      c.tallies.push_back(tallies.tally(g, b));
      c.cells.push_back(tallies.group_estimate_z(g, b, bins[b].area_m2, z));
      if (direct) c.direct.push_back(direct_light(tallies, g, b));
    }
    r.contributions.push_back(std::move(c));
  }
}

}  // namespace lightsolver::detail
