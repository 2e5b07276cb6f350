#pragma once
// The hierarchical grid behind coincident-surface detection (coincident.cpp): every triangle
// sits in the cells of its own level; a query visits the cells of coarser levels too, so all
// pairs whose boxes overlap are met without comparing every triangle with every other.
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/common.hpp>
#include <glm/ext/vector_int3_sized.hpp>
#include <glm/vec3.hpp>
#include <tuple>
#include <utility>
#include <vector>

namespace lightsolver::detail::coincident_grid {

using glm::dvec3;

// A triangle lives in the cells of size 2^level (level: the smallest one at least as large as
// its padded box) that its box touches, at most 8. Each triangle then looks up the cells of its
// own and every coarser level it touches, so every pair whose boxes overlap is met once.
constexpr int kLevelBias = 24;  // level l is bit l + kLevelBias of a 64-bit mask

inline int level_of(const dvec3& lo, const dvec3& hi) {
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-12});
  int e = 0;
  std::frexp(extent, &e);                              // extent <= 2^e
  return std::clamp(e, -kLevelBias, 63 - kLevelBias);  // 6e-8 m to 5e11 m: never reached
}

inline std::uint64_t mix(std::uint64_t h) {  // splitmix64 finaliser
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

// Colliding keys merge two cells: more candidates, never a missed one.
inline std::uint64_t cell_key(int level, std::int64_t x, std::int64_t y, std::int64_t z) {
  std::uint64_t h = mix(static_cast<std::uint64_t>(level + 1024));
  h = mix(h ^ static_cast<std::uint64_t>(x));
  h = mix(h ^ static_cast<std::uint64_t>(y));
  return mix(h ^ static_cast<std::uint64_t>(z));
}

template <class F>
void for_each_cell(int level, const dvec3& lo, const dvec3& hi, F&& f) {
  const double inv = std::ldexp(1.0, -level);
  const auto c0 = glm::i64vec3(glm::floor(lo * inv)), c1 = glm::i64vec3(glm::floor(hi * inv));
  for (auto x = c0.x; x <= c1.x; ++x)
    for (auto y = c0.y; y <= c1.y; ++y)
      for (auto z = c0.z; z <= c1.z; ++z) f(cell_key(level, x, y, z));
}

struct Entry {
  std::uint64_t key;
  std::uint32_t mesh, tri;
  bool operator<(const Entry& o) const {
    return std::tie(key, mesh, tri) < std::tie(o.key, o.mesh, o.tri);
  }
};

// Sorted entries plus an open-addressing table from cell key to its entry range.
class Grid {
 public:
  explicit Grid(std::vector<Entry> entries) : entries_(std::move(entries)) {
    tbb::parallel_sort(entries_.begin(), entries_.end());
    run_end_.resize(entries_.size());
    std::size_t cells = 0;
    for (std::size_t i = entries_.size(); i-- > 0;) {
      const bool last = i + 1 == entries_.size();
      const bool same_run = !last && entries_[i + 1].key == entries_[i].key &&
                            entries_[i + 1].mesh == entries_[i].mesh;
      run_end_[i] = same_run ? run_end_[i + 1] : static_cast<std::uint32_t>(i + 1);
      cells += last || entries_[i + 1].key != entries_[i].key;
    }
    std::size_t capacity = 16;
    while (capacity < 2 * cells) capacity *= 2;
    slots_.assign(capacity, {0, 0, 0});
    for (std::size_t i = 0; i < entries_.size();) {
      std::size_t j = i;
      while (j < entries_.size() && entries_[j].key == entries_[i].key) ++j;
      std::size_t s = entries_[i].key & (capacity - 1);
      while (slots_[s].end != 0) s = (s + 1) & (capacity - 1);
      slots_[s] = {entries_[i].key, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)};
      i = j;
    }
  }
  // Entries [begin, end) of a cell; begin == end when empty.
  std::pair<std::uint32_t, std::uint32_t> find(std::uint64_t key) const {
    for (std::size_t s = key & (slots_.size() - 1);; s = (s + 1) & (slots_.size() - 1)) {
      if (slots_[s].end == 0) return {0, 0};
      if (slots_[s].key == key) return {slots_[s].begin, slots_[s].end};
    }
  }
  const Entry& entry(std::uint32_t i) const { return entries_[i]; }
  std::uint32_t run_end(std::uint32_t i) const { return run_end_[i]; }

 private:
  struct Slot {
    std::uint64_t key;
    std::uint32_t begin, end;
  };
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> run_end_;  // end of the entries with this entry's key and mesh
  std::vector<Slot> slots_;
};

}  // namespace lightsolver::detail::coincident_grid
