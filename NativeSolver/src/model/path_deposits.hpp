#pragma once
// Per-path bookkeeping of deposits, so each bin gets this path's total c and c^2 (the per-path
// variance estimate needs whole-path totals, not individual hits). Also the virtual-grid test.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "lightsolver/statistics.hpp"
#include "model/prepared_scene.hpp"
#include "shared/grids.h"

namespace lightsolver::detail {

class PathDeposits {
 public:
  void add(std::uint32_t bin) {
    for (auto& e : entries_) {
      if (e.bin == bin) {
        ++e.count;
        return;
      }
    }
    entries_.push_back({bin, 1});  // paths touch few bins: a linear scan beats a hash map
  }

  // `offset`: the path's group's first tally (group * scene bins).
  void flush(std::vector<Tally>& bins, std::size_t offset = 0) {
    for (const auto& e : entries_) {
      bins[offset + e.bin].sum += e.count;
      bins[offset + e.bin].sum_sq += std::uint64_t(e.count) * e.count;
    }
    entries_.clear();
  }

 private:
  struct Entry {
    std::uint32_t bin, count;
  };
  std::vector<Entry> entries_;
};

// Counts the crossing of every virtual grid by the segment origin + t * dir, 0 <= t <= t_max,
// from the grid's front (Shaders/shared/grids.h, the text the shaders include too). A grid lying
// on a surface still counts the photons arriving there (shared::grid_reach).
// `bounce`: reflections before this segment (0: straight from the luminaire); indirect-only
// grids (observers) skip direct segments, and so does every grid when `first_bounce` is 1 (the
// path's group has its direct light by next-event estimation) but those whose direct light went
// back to the photons (PreparedGrid::direct_by_photons). `connected`: the path's group
// has its reflected light beyond each grid's connect_r0 by connection (PreparedGroup::connect),
// so a reflected segment counts only crossings closer than that to its origin (d is unit: t is
// the distance); together the two count every (vertex, grid point) pair exactly once.
inline void cross_grids(const std::vector<PreparedGrid>& grids, const vec3& o, const vec3& d,
                        float t_max, std::uint32_t bounce, PathDeposits& deposits,
                        std::uint32_t first_bounce = 0, bool connected = false) {
  const bool by_shadow_rays = bounce < first_bounce;
  const float t_end = shared::grid_reach(t_max);
  const bool capped = connected && bounce >= 1;
  for (const auto& g : grids) {
    if (bounce == 0 && (g.indirect_only || (by_shadow_rays && !g.direct_by_photons))) continue;
    const float t_grid = capped && g.connect_r0 > 0.0f ? std::min(t_end, g.connect_r0) : t_end;
    std::uint32_t cell;
    if (!shared::grid_crossing(o, d, t_grid, g.corner, g.normal, g.du, g.dv, g.nu, g.nv, cell)) {
      continue;
    }
    deposits.add(g.bin);
    deposits.add(g.bin + 1 + cell);
  }
}

}  // namespace lightsolver::detail
