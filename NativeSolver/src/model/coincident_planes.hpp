#pragma once
// The plane filter in front of coincident-surface detection's grid (coincident.cpp). Two
// triangles can only coincide where their planes nearly agree: normals parallel or antiparallel
// within 0.01 rad, and plane offsets d = n·p within what that angle and the tolerance allow at
// the scene's coordinates. Each triangle's plane is a point (n, d) in 4-D; every triangle is
// entered in the cells of that space its tolerance box touches (one or a few), each cell keeps
// a summary of the meshes entered there, and a triangle whose own point (or its antipode
// (-n, -d)) falls in no cell holding a mesh it matters with cannot be part of any pair. Most of
// a furnished room's triangles (chairs, curved furniture) are such: the grid then skips them.
// The filter only drops triangles; the pairs the grid finds among the rest are the same ones.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "model/coincident_grid.hpp"

namespace lightsolver::detail::coincident_planes {

using glm::dvec3;

/// A triangle's plane: unit front normal and offset n·p.
struct Plane {
  dvec3 n{0.0};
  double d = 0.0;
  /// False for a degenerate triangle (a normal that is not finite): the filter cannot place
  /// it, so it keeps everything such a triangle may meet.
  bool ok() const { return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z); }
};

/// Which meshes one cell holds, enough to answer "is any of them relevant to mesh m": relevant
/// pairs are two different meshes of which one is a target or whose materials differ. 16 bytes:
/// the cell key's low four bits carry the flags (keys equal above them merge: more survivors,
/// never fewer).
struct Summary {
  static constexpr std::uint64_t kUsed = 1, kSecondMesh = 2, kTarget = 4, kSecondMaterial = 8;
  static constexpr std::uint64_t kFlags = 15;
  std::uint64_t bits = 0;      // key & ~kFlags | flags; 0: an empty slot
  std::uint32_t mesh = 0;      // the first mesh entered
  std::int32_t material = -1;  // the first non-target mesh's material, -1 when none

  /// A cell whose first mesh is `m` (enter m with add() too).
  static Summary start(std::uint64_t key, std::uint32_t m) { return {key | kUsed, m, -1}; }
  bool empty() const { return bits == 0; }
  std::uint64_t key() const { return bits & ~kFlags; }
  void add(std::uint32_t m, bool is_target, std::int32_t mat) {
    if (m != mesh) bits |= kSecondMesh;
    if (is_target) {
      bits |= kTarget;
    } else if (material < 0) {
      material = mat;
    } else if (mat != material) {
      bits |= kSecondMaterial;
    }
  }
  bool relevant_to(std::uint32_t m, bool is_target, std::int32_t mat) const {
    if (empty()) return false;
    if (is_target) return mesh != m || (bits & kSecondMesh);
    return (bits & kTarget) || (material >= 0 && (material != mat || (bits & kSecondMaterial)));
  }
};

/// Open-addressing table from cell key to its summary.
class Cells {
 public:
  explicit Cells(std::size_t expected) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    slots_.resize(capacity);
  }
  /// Enters mesh `m` in the cell `key`.
  void add(std::uint64_t key, std::uint32_t m, bool is_target, std::int32_t mat) {
    key &= ~Summary::kFlags;
    if (2 * (size_ + 1) > slots_.size()) grow();
    for (std::size_t s = slot(key);; s = (s + 1) & (slots_.size() - 1)) {
      Summary& c = slots_[s];
      if (c.empty()) {
        c = Summary::start(key, m);
        ++size_;
      } else if (c.key() != key) {
        continue;
      }
      return c.add(m, is_target, mat);
    }
  }
  std::size_t size() const { return size_; }
  const Summary* find(std::uint64_t key) const {
    key &= ~Summary::kFlags;
    for (std::size_t s = slot(key);; s = (s + 1) & (slots_.size() - 1)) {
      if (slots_[s].empty()) return nullptr;
      if (slots_[s].key() == key) return &slots_[s];
    }
  }

 private:
  std::size_t slot(std::uint64_t key) const { return (key >> 4) & (slots_.size() - 1); }
  void grow() {
    std::vector<Summary> old(2 * slots_.size());
    old.swap(slots_);
    for (const Summary& c : old) {
      if (c.empty()) continue;
      std::size_t s = slot(c.key());
      while (!slots_[s].empty()) s = (s + 1) & (slots_.size() - 1);
      slots_[s] = c;
    }
  }
  std::vector<Summary> slots_;
  std::size_t size_ = 0;
};

/// The 4-D cells: normals in cells of `normal_cell` per component, offsets of `offset_cell`.
class PlaneGrid {
 public:
  /// `normal_tol`: the largest |n1 - s n2| (s = ±1) of a coincident pair, per component;
  /// `offset_tol`: the largest |d1 - s d2|.
  PlaneGrid(double normal_tol, double offset_tol)
      : normal_tol_(normal_tol),
        offset_tol_(offset_tol),
        inv_n_(1.0 / (kNormalCells * normal_tol)),
        inv_d_(1.0 / (kOffsetCells * offset_tol)) {}

  /// The cells a plane's tolerance box touches, per axis [lo, hi] (n.x, n.y, n.z, d).
  struct Box {
    std::int64_t lo[4], hi[4];
    bool operator==(const Box&) const = default;
  };
  Box near(const Plane& p) const {
    Box b;
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = index(p.n[i] - normal_tol_, inv_n_);
      b.hi[i] = index(p.n[i] + normal_tol_, inv_n_);
    }
    b.lo[3] = index(p.d - offset_tol_, inv_d_);
    b.hi[3] = index(p.d + offset_tol_, inv_d_);
    return b;
  }
  /// Calls f(key) for every cell of the box.
  template <class F>
  static void for_each(const Box& b, F&& f) {
    for (auto x = b.lo[0]; x <= b.hi[0]; ++x)
      for (auto y = b.lo[1]; y <= b.hi[1]; ++y)
        for (auto z = b.lo[2]; z <= b.hi[2]; ++z)
          for (auto w = b.lo[3]; w <= b.hi[3]; ++w) f(key(x, y, z, w));
  }
  /// The cell of the plane with its normal times `sign`.
  std::uint64_t cell(const Plane& p, double sign) const {
    return key(index(sign * p.n.x, inv_n_), index(sign * p.n.y, inv_n_),
               index(sign * p.n.z, inv_n_), index(sign * p.d, inv_d_));
  }

 private:
  // Cells this many tolerances wide: a box touches at most two per axis, mostly one.
  static constexpr double kNormalCells = 4.0, kOffsetCells = 2.0;
  static std::int64_t index(double v, double inv) {
    return static_cast<std::int64_t>(std::floor(std::clamp(v * inv, -1e15, 1e15)));
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t w) {
    using coincident_grid::mix;
    std::uint64_t h = mix(static_cast<std::uint64_t>(x) + 0x9e3779b97f4a7c15ull);
    h = mix(h ^ static_cast<std::uint64_t>(y));
    h = mix(h ^ static_cast<std::uint64_t>(z));
    return mix(h ^ static_cast<std::uint64_t>(w));
  }
  double normal_tol_, offset_tol_, inv_n_, inv_d_;
};

/// Per triangle g, 1 when its plane comes within (normal_tol, offset_tol) of the plane of a
/// triangle of a mesh it is relevant with (either sign), else 0: such a triangle cannot be in
/// any pair. `mesh_of(g)`: its mesh; `is_target(m)`, `material(m)`: of a mesh.
template <class MeshOf, class IsTarget, class MaterialOf>
std::vector<std::uint8_t> near_planes(const std::vector<Plane>& planes, double normal_tol,
                                      double offset_tol, MeshOf mesh_of, IsTarget is_target,
                                      MaterialOf material) {
  const PlaneGrid grid(normal_tol, offset_tol);
  Cells cells(1024);   // grows with the cells entered (far fewer than triangles)
  Summary degenerate;  // triangles without a plane: they may meet anything
  // Neighbouring triangles of a mesh often share their cells (a quad's two halves, a flat
  // face's fan): entering the same mesh in the same cells again changes nothing.
  PlaneGrid::Box last{};
  std::uint32_t last_mesh = ~0u;
  for (std::size_t g = 0; g < planes.size(); ++g) {
    const std::uint32_t m = mesh_of(g);
    if (!planes[g].ok()) {
      if (degenerate.empty()) degenerate = Summary::start(0, m);
      degenerate.add(m, is_target(m), material(m));
      continue;
    }
    const PlaneGrid::Box box = grid.near(planes[g]);
    if (m == last_mesh && box == last) continue;
    last = box;
    last_mesh = m;
    grid.for_each(box, [&](std::uint64_t key) { cells.add(key, m, is_target(m), material(m)); });
  }
  std::vector<std::uint8_t> keep(planes.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, planes.size(), 4096), [&](const auto& r) {
    for (std::size_t g = r.begin(); g != r.end(); ++g) {
      const std::uint32_t m = mesh_of(g);
      const bool t = is_target(m);
      const std::int32_t mat = material(m);
      bool near = !planes[g].ok() || degenerate.relevant_to(m, t, mat);
      for (double sign : {1.0, -1.0}) {
        if (near) break;
        const Summary* c = cells.find(grid.cell(planes[g], sign));
        near = c != nullptr && c->relevant_to(m, t, mat);
      }
      keep[g] = near;
    }
  });
  return keep;
}

}  // namespace lightsolver::detail::coincident_planes
