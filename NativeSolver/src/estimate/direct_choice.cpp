#include "estimate/direct_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lightsolver::detail {
namespace {

// Targets named in full in the words; the rest are counted.
constexpr std::size_t kNamed = 8;

// The bins whose direct light a target's choice covers: a surface target's one bin, a grid's
// cells (their sum of variances: the cells are what a grid reports). None for observers.
std::vector<std::uint32_t> judged_bins(const PreparedScene& s, const PreparedTarget& t) {
  std::vector<std::uint32_t> bins;
  if (t.mesh >= 0) {
    const PreparedMesh& m = s.meshes[std::size_t(t.mesh)];
    if (m.bin >= 0 && !m.normals.empty()) bins.push_back(std::uint32_t(m.bin));
    return bins;
  }
  for (std::uint32_t r = t.first_grid; r < t.first_grid + t.grid_rows; ++r) {
    const PreparedGrid& g = s.grids[r];
    if (g.indirect_only) continue;
    for (std::uint32_t c = 0; c < g.nu * g.nv; ++c) bins.push_back(g.bin + 1 + c);
  }
  return bins;
}

// Bin b's photon variance of the next-event groups' direct light, times the run's photons:
// sum over groups of flux E (1 - p) / (share A). Infinite where a lit group gets no photons.
double unit_photon_variance(const PreparedScene& s, const std::vector<DirectPart>& parts,
                            std::uint32_t b) {
  const double area = s.bins[b].area_m2;
  double u = 0.0;
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const PreparedGroup& group = s.groups[g];
    if (!group.next_event) continue;
    const double e = parts[g * s.bins.size() + b].lux;
    if (!(e > 0.0) || !(area > 0.0)) continue;
    if (!(group.share > 0.0)) return std::numeric_limits<double>::infinity();
    const double p = std::min(1.0, e * area / group.flux_lm);
    u += group.flux_lm * e * (1.0 - p) / (group.share * area);
  }
  return u;
}

void set_by_photons(PreparedScene& s, const PreparedTarget& t) {
  if (t.mesh >= 0) {
    const std::int32_t bin = s.meshes[std::size_t(t.mesh)].bin;
    for (PreparedMesh& m : s.meshes) m.direct_by_photons = m.direct_by_photons || m.bin == bin;
    return;
  }
  for (std::uint32_t r = t.first_grid; r < t.first_grid + t.grid_rows; ++r) {
    if (!s.grids[r].indirect_only) s.grids[r].direct_by_photons = true;
  }
}

std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < kNamed; ++i) out += (i ? ", " : "") + items[i];
  if (items.size() > kNamed) out += " and " + std::to_string(items.size() - kNamed) + " more";
  return out;
}

}  // namespace

std::uint64_t judging_seed(std::uint64_t seed) {
  return seed ^ 0xa5c3'5e1d'9b70'2f84ull;  // any fixed change: Philox keys the streams by it
}

DirectWidths direct_widths(const PreparedScene& s, const std::vector<DirectPart>& parts,
                           std::uint64_t photons, std::uint32_t strata_scale,
                           const PreparedTarget& target) {
  DirectWidths w;
  const double scale2 = double(strata_scale) * strata_scale;
  for (const std::uint32_t b : judged_bins(s, target)) {
    double shadow_rays = 0.0;
    for (std::size_t g = 0; g < s.groups.size(); ++g) {
      if (s.groups[g].next_event) shadow_rays += parts[g * s.bins.size() + b].variance / scale2;
    }
    w.shadow_rays += std::sqrt(shadow_rays);
    w.photons +=
        std::sqrt(unit_photon_variance(s, parts, b) / double(std::max<std::uint64_t>(photons, 1)));
  }
  return w;
}

std::string choose_direct_targets(PreparedScene& s, const std::vector<DirectPart>& parts,
                                  std::uint64_t photons, std::uint32_t strata_scale,
                                  const std::vector<std::string>& names) {
  std::vector<std::string> kept, given;
  for (std::size_t i = 0; i < s.targets.size(); ++i) {
    const PreparedTarget& t = s.targets[i];
    if (judged_bins(s, t).empty()) continue;  // observers: reflected light only
    const DirectWidths w = direct_widths(s, parts, photons, strata_scale, t);
    const std::string& name = i < names.size() ? names[i] : std::to_string(i);
    if (w.shadow_rays <= w.photons) {  // ties (an unlit target: both 0) keep the shadow rays
      kept.push_back(name);
      continue;
    }
    set_by_photons(s, t);
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.1fx", w.shadow_rays / w.photons);
    given.push_back(name + " (" + ratio + ")");
  }
  if (given.empty()) return {};
  std::string out = "photons where shadow rays would be wider: " + listed(given);
  if (!kept.empty()) out += "; shadow rays: " + listed(kept);
  return out;
}

void clear_direct_by_photons(PreparedScene& s) {
  for (PreparedMesh& m : s.meshes) m.direct_by_photons = false;
  for (PreparedGrid& g : s.grids) g.direct_by_photons = false;
}

bool any_target_by_photons(const PreparedScene& s) {
  return std::any_of(s.meshes.begin(), s.meshes.end(),
                     [](const PreparedMesh& m) { return m.direct_by_photons; }) ||
         std::any_of(s.grids.begin(), s.grids.end(),
                     [](const PreparedGrid& g) { return g.direct_by_photons; });
}

bool any_target_by_shadow_rays(const PreparedScene& s) {
  for (const PreparedMesh& m : s.meshes) {
    if (m.bin >= 0 && !m.normals.empty() && !m.direct_by_photons) return true;
  }
  return std::any_of(s.grids.begin(), s.grids.end(), [](const PreparedGrid& g) {
    return !g.indirect_only && !g.direct_by_photons;
  });
}

std::uint64_t goal_photons(const PreparedScene& s, const std::vector<DirectPart>& parts,
                           double goal, double z, bool per_cell, std::uint64_t budget) {
  double most = 1.0;
  const auto need = [&](std::uint32_t b) {
    double e = 0.0;
    for (std::size_t g = 0; g < s.groups.size(); ++g) {
      if (s.groups[g].next_event) e += parts[g * s.bins.size() + b].lux;
    }
    if (!(e > 0.0)) return;
    most = std::max(most, z * z * unit_photon_variance(s, parts, b) / (goal * e * goal * e));
  };
  for (const PreparedTarget& t : s.targets) {
    if (judged_bins(s, t).empty()) continue;
    if (t.mesh >= 0 || !per_cell) need(t.mesh >= 0 ? std::uint32_t(s.meshes[t.mesh].bin) : t.bin);
    if (t.mesh < 0 && per_cell) {
      for (const std::uint32_t b : judged_bins(s, t)) need(b);
    }
  }
  return most >= double(budget) ? budget : std::uint64_t(most);
}

std::vector<bool> direct_by_photons_flags(const PreparedScene& s) {
  std::vector<bool> out;
  for (const PreparedMesh& m : s.meshes) out.push_back(m.direct_by_photons);
  for (const PreparedGrid& g : s.grids) out.push_back(g.direct_by_photons);
  return out;
}

}  // namespace lightsolver::detail
