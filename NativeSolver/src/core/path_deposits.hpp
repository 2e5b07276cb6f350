#pragma once
// Per-path bookkeeping of deposits, so each bin gets this path's total c and c^2 (the per-path
// variance estimate needs whole-path totals, not individual hits). Also the virtual-grid test.
#include <cstdint>
#include <glm/geometric.hpp>
#include <vector>

#include "core/prepared_scene.hpp"
#include "lightsolver/statistics.hpp"

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
// from the grid's front. A grid lying on a surface still counts the photons arriving there:
// the end of the segment is extended by a relative 1e-5 to absorb float error in t_max.
// `bounce`: reflections before this segment (0: straight from the luminaire); indirect-only
// grids (observers) skip direct segments.
inline void cross_grids(const std::vector<PreparedGrid>& grids, const vec3& o, const vec3& d,
                        float t_max, std::uint32_t bounce, PathDeposits& deposits) {
  const float t_end = t_max * (1.0f + 1e-5f) + 1e-6f;
  for (const auto& g : grids) {
    if (g.indirect_only && bounce == 0) continue;
    const float denom = glm::dot(d, g.normal);
    if (!(denom < 0.0f)) continue;  // parallel, or crossing from behind
    const float t = glm::dot(g.corner - o, g.normal) / denom;
    if (!(t >= 0.0f && t <= t_end)) continue;
    const vec3 rel = o + t * d - g.corner;
    const float a = glm::dot(rel, g.du), b = glm::dot(rel, g.dv);
    if (!(a >= 0.0f && a < 1.0f && b >= 0.0f && b < 1.0f)) continue;
    const auto iu = std::min<std::uint32_t>(static_cast<std::uint32_t>(a * g.nu), g.nu - 1);
    const auto iv = std::min<std::uint32_t>(static_cast<std::uint32_t>(b * g.nv), g.nv - 1);
    deposits.add(g.bin);
    deposits.add(g.bin + 1 + iv * g.nu + iu);
  }
}

}  // namespace lightsolver::detail
