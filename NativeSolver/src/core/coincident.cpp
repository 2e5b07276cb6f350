#include "core/coincident.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <glm/ext/vector_int3_sized.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>
#include <map>
#include <tuple>

namespace lightsolver::detail {
namespace {

using glm::dvec2;
using glm::dvec3;

// Normals parallel or antiparallel within 0.01 rad; the plane distance test does the real work.
const double kCosMaxAngle = std::cos(0.01);
// Detection tolerance = 2 x the tracer's ray offset; the hidden triangle moves by 2 x that.
constexpr double kToleranceMargin = 2.0, kMoveFactor = 2.0;
// Overlaps below this fraction of the smaller triangle are rounding (triangles sharing an edge).
constexpr double kMinOverlapFraction = 1e-9;

struct Triangle {
  std::array<dvec3, 3> p;  // re-centred coordinates
  dvec3 n;                 // unit front normal
  double area_m2 = 0.0;
};

// Every triangle of the included meshes under one global index, vertices in re-centred
// coordinates computed on demand (a million triangles must not cost a million records).
class SceneTriangles {
 public:
  SceneTriangles(const Scene& s, const dvec3& origin, const std::vector<bool>& included)
      : s_(s), origin_(origin) {
    first_.push_back(0);
    for (std::size_t m = 0; m < s.meshes.size(); ++m) {
      const std::size_t n = included[m] ? s.meshes[m].triangles.size() : 0;
      mesh_of_.insert(mesh_of_.end(), n, static_cast<std::uint32_t>(m));
      first_.push_back(first_.back() + n);
    }
  }
  std::size_t size() const { return mesh_of_.size(); }
  std::uint32_t mesh(std::size_t g) const { return mesh_of_[g]; }
  std::size_t local(std::size_t g) const { return g - first_[mesh_of_[g]]; }
  const glm::u32vec3& indices(std::size_t g) const {
    return s_.meshes[mesh_of_[g]].triangles[local(g)];
  }
  dvec3 vertex(std::size_t g, int k) const {
    return s_.meshes[mesh_of_[g]].vertices[indices(g)[k]] - origin_;
  }
  void bounds(std::size_t g, dvec3& lo, dvec3& hi) const {
    lo = hi = vertex(g, 0);
    for (int k = 1; k < 3; ++k) {
      lo = glm::min(lo, vertex(g, k));
      hi = glm::max(hi, vertex(g, k));
    }
  }
  Triangle get(std::size_t g) const {
    Triangle t{{vertex(g, 0), vertex(g, 1), vertex(g, 2)}, dvec3(0.0), 0.0};
    const dvec3 c = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
    t.area_m2 = 0.5 * glm::length(c);
    t.n = c / (2.0 * t.area_m2);
    return t;
  }

 private:
  const Scene& s_;
  dvec3 origin_;
  std::vector<std::uint32_t> mesh_of_;
  std::vector<std::size_t> first_;
};

// --- 2-D overlap by Sutherland-Hodgman --------------------------------------------------------

struct Polygon {
  std::array<dvec2, 12> v;  // a triangle clipped by three half-planes has at most 6 vertices
  int n = 0;
};

double cross2(const dvec2& a, const dvec2& b) { return a.x * b.y - a.y * b.x; }

double signed_area(const Polygon& p) {
  double twice = 0.0;
  for (int i = 0; i < p.n; ++i) twice += cross2(p.v[i], p.v[(i + 1) % p.n]);
  return 0.5 * twice;
}

// Keeps the part of `in` left of the directed line a -> b.
Polygon clip(const Polygon& in, const dvec2& a, const dvec2& b) {
  Polygon out;
  const dvec2 e = b - a;
  for (int i = 0; i < in.n; ++i) {
    const dvec2 &p = in.v[i], &q = in.v[(i + 1) % in.n];
    const double sp = cross2(e, p - a), sq = cross2(e, q - a);
    if (sp >= 0.0) out.v[out.n++] = p;
    if ((sp >= 0.0) != (sq >= 0.0)) out.v[out.n++] = p + (sp / (sp - sq)) * (q - p);
  }
  return out;
}

// Offset of the tracer, measured along the unit normal n, where coordinates reach `magnitude`
// per axis: offset_ray_origin shifts coordinate i by n_i times its bound.
double ray_offset_along(const dvec3& n, const dvec3& magnitude) {
  double h = 0.0;
  for (int i = 0; i < 3; ++i) h += std::abs(n[i]) * ray_offset_bound_m(magnitude[i]);
  return h;
}

// Area of t and o overlapping within the tolerance of t's plane, or 0. `tol_m` is the largest
// distance between the planes allowed anywhere in the overlap.
double coplanar_overlap_m2(const Triangle& t, const Triangle& o, double tol_m) {
  if (std::abs(glm::dot(t.n, o.n)) < kCosMaxAngle) return 0.0;
  const dvec3 u = glm::normalize(t.p[1] - t.p[0]), v = glm::cross(t.n, u);
  auto flat = [&](const dvec3& p) {
    return dvec2(glm::dot(p - t.p[0], u), glm::dot(p - t.p[0], v));
  };
  Polygon poly;
  for (const dvec3& p : t.p) poly.v[poly.n++] = flat(p);  // counter-clockwise about t.n
  std::array<dvec2, 3> clipper = {flat(o.p[0]), flat(o.p[1]), flat(o.p[2])};
  if (glm::dot(t.n, o.n) < 0.0) std::swap(clipper[1], clipper[2]);  // make it counter-clockwise
  for (int k = 0; k < 3 && poly.n > 0; ++k) poly = clip(poly, clipper[k], clipper[(k + 1) % 3]);
  if (poly.n < 3) return 0.0;
  const double area = signed_area(poly);
  if (!(area > kMinOverlapFraction * std::min(t.area_m2, o.area_m2))) return 0.0;
  // The gap between the planes is affine over the overlap: its vertices bound it.
  for (int i = 0; i < poly.n; ++i) {
    const dvec3 q = t.p[0] + poly.v[i].x * u + poly.v[i].y * v;
    if (std::abs(glm::dot(q - o.p[0], o.n)) > tol_m) return 0.0;
  }
  return area;
}

// --- hierarchical grid -------------------------------------------------------------------------

// A triangle lives in the cells of size 2^level (level: the smallest one at least as large as
// its padded box) that its box touches, at most 8. Each triangle then looks up the cells of its
// own and every coarser level it touches, so every pair whose boxes overlap is met once.
int level_of(const dvec3& lo, const dvec3& hi) {
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-12});
  int e = 0;
  std::frexp(extent, &e);  // extent <= 2^e
  return e;
}

std::uint64_t mix(std::uint64_t h) {  // splitmix64 finaliser
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

// Colliding keys merge two cells: more candidates, never a missed one.
std::uint64_t cell_key(int level, std::int64_t x, std::int64_t y, std::int64_t z) {
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
    std::sort(entries_.begin(), entries_.end());
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

// --- the rule ---------------------------------------------------------------------------------

struct Move {
  std::uint32_t mesh, vertex;
  dvec3 dir;    // unit
  double dist;  // metres, at least
};

class Detector {
 public:
  Detector(const Scene& s, const dvec3& origin, const std::vector<bool>& is_target,
           const std::vector<bool>& movable)
      : s_(s), is_target_(is_target), tris_(s, origin, included(s, movable)) {
    for (std::size_t g = 0; g < tris_.size(); ++g) {
      dvec3 lo, hi;
      tris_.bounds(g, lo, hi);
      magnitude_ = glm::max(magnitude_, glm::max(glm::abs(lo), glm::abs(hi)));
    }
    // Boxes grow by the largest tolerance anywhere, so no coplanar pair is missed.
    pad_m_ = kToleranceMargin * ray_offset_along(dvec3(1.0), magnitude_);
  }

  CoincidentGeometry run() {
    std::vector<Entry> entries;
    level_.resize(tris_.size());
    std::vector<int> levels;
    for (std::size_t g = 0; g < tris_.size(); ++g) {
      dvec3 lo, hi;
      padded_bounds(g, lo, hi);
      level_[g] = level_of(lo, hi);
      levels.push_back(level_[g]);
      for_each_cell(level_[g], lo, hi, [&](std::uint64_t key) {
        entries.push_back({key, tris_.mesh(g), static_cast<std::uint32_t>(g)});
      });
    }
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    const Grid grid(std::move(entries));
    std::vector<std::uint32_t> seen(tris_.size(), 0);
    for (std::size_t g = 0; g < tris_.size(); ++g) {
      dvec3 lo, hi;
      padded_bounds(g, lo, hi);
      for (auto l = std::lower_bound(levels.begin(), levels.end(), level_[g]); l != levels.end();
           ++l) {
        for_each_cell(*l, lo, hi, [&](std::uint64_t key) { visit_cell(grid, key, g, seen); });
      }
    }
    return finish();
  }

 private:
  static std::vector<bool> included(const Scene& s, const std::vector<bool>& movable) {
    std::vector<bool> in(s.meshes.size());
    for (std::size_t m = 0; m < in.size(); ++m) in[m] = !movable[m];
    return in;
  }

  void padded_bounds(std::size_t g, dvec3& lo, dvec3& hi) const {
    tris_.bounds(g, lo, hi);
    lo -= pad_m_;
    hi += pad_m_;
  }

  // Pairs that can matter: one side is a target, or the materials differ.
  bool relevant(std::uint32_t a, std::uint32_t b) const {
    return a != b &&
           (is_target_[a] || is_target_[b] || s_.meshes[a].material != s_.meshes[b].material);
  }

  void visit_cell(const Grid& grid, std::uint64_t key, std::size_t g,
                  std::vector<std::uint32_t>& seen) {
    const std::uint32_t mesh = tris_.mesh(g);
    auto [i, end] = grid.find(key);
    while (i < end) {
      const Entry& e = grid.entry(i);
      if (!relevant(mesh, e.mesh)) {
        i = grid.run_end(i);  // skip this mesh's entries in the cell at once
        continue;
      }
      ++i;
      // Same-level pairs are met from both sides: keep one. Stamps drop a cell's repeats.
      if ((level_[e.tri] == level_[g] && e.tri <= g) || seen[e.tri] == g + 1) continue;
      seen[e.tri] = static_cast<std::uint32_t>(g + 1);
      test_pair(g, e.tri);
    }
  }

  void test_pair(std::size_t g1, std::size_t g2) {
    dvec3 lo1, hi1, lo2, hi2;
    padded_bounds(g1, lo1, hi1);
    padded_bounds(g2, lo2, hi2);
    if (glm::any(glm::lessThan(hi1, lo2)) || glm::any(glm::lessThan(hi2, lo1))) return;
    // The reference triangle t: the target's where there is one, else the lower mesh's.
    const std::uint32_t m1 = tris_.mesh(g1), m2 = tris_.mesh(g2);
    const bool t_first = is_target_[m1] != is_target_[m2] ? is_target_[m1] : m1 < m2;
    const std::size_t gt = t_first ? g1 : g2, go = t_first ? g2 : g1;
    const Triangle t = tris_.get(gt), o = tris_.get(go);
    dvec3 magnitude(0.0);
    for (const dvec3& p : t.p) magnitude = glm::max(magnitude, glm::abs(p));
    for (const dvec3& p : o.p) magnitude = glm::max(magnitude, glm::abs(p));
    const double tol_m = kToleranceMargin * ray_offset_along(t.n, magnitude);
    const double area = coplanar_overlap_m2(t, o, tol_m);
    if (area == 0.0) return;
    apply_rule(gt, t, go, o, area, kMoveFactor * tol_m);
  }

  // Same-facing: the other triangle steps back behind the target (the lit side, with its grids
  // and flush luminaires, is untouched). Back to back: the smaller triangle steps toward its own
  // front, the side the other one hides, so the disturbance stays as local as possible.
  void apply_rule(std::size_t gt, const Triangle& t, std::size_t go, const Triangle& o, double area,
                  double move_m) {
    const std::uint32_t mt = tris_.mesh(gt), mo = tris_.mesh(go);
    const bool same_facing = glm::dot(t.n, o.n) > 0.0;
    using K = Coincidence::Kind;
    if (!is_target_[mt]) {
      found_[{mt, mo, K::Materials}] += area;
    } else if (is_target_[mo] && same_facing) {
      found_[{mt, mo, K::TargetsArbitrary}] += area;
    } else {
      found_[{mt, mo, is_target_[mo] ? K::TargetsResolved : K::TargetOnSurface}] += area;
      if (same_facing || o.area_m2 < t.area_m2) {
        add_move(go, -t.n, move_m);
      } else {
        add_move(gt, t.n, move_m);
      }
    }
  }

  void add_move(std::size_t g, const dvec3& dir, double dist) {
    for (int k = 0; k < 3; ++k) moves_.push_back({tris_.mesh(g), tris_.indices(g)[k], dir, dist});
  }

  // Per mesh, the lowest index of the vertices at each position: a mesh whose faces do not
  // share vertices (STL, one quad per face) must move as if they did, or it would crack open.
  std::vector<std::uint32_t> weld(std::uint32_t mesh) const {
    const auto& v = s_.meshes[mesh].vertices;
    std::vector<std::uint32_t> order(v.size()), canon(v.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    auto key = [&](std::uint32_t i) { return std::tie(v[i].x, v[i].y, v[i].z); };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return std::pair(key(a), a) < std::pair(key(b), b);
    });
    for (std::size_t i = 0; i < order.size(); ++i) {
      const bool same = i > 0 && v[order[i]] == v[order[i - 1]];
      canon[order[i]] = same ? canon[order[i - 1]] : order[i];
    }
    return canon;
  }

  // Each moved vertex must end at least `dist` along every `dir` asked of it (a box corner on a
  // floor and against a wall: two). Projections onto those half-spaces converge at once for
  // one direction or perpendicular ones, and in a few passes otherwise.
  static dvec3 displacement(const Move* first, const Move* last) {
    dvec3 d(0.0);
    for (int pass = 0; pass < 16; ++pass) {
      bool done = true;
      for (const Move* m = first; m != last; ++m) {
        const double along = glm::dot(d, m->dir);
        if (along < m->dist) {
          d += (m->dist - along) * m->dir;
          done = false;
        }
      }
      if (done) break;
    }
    return d;
  }

  CoincidentGeometry finish() {
    CoincidentGeometry out;
    for (const auto& [key, area] : found_) {
      out.pairs.push_back({std::get<2>(key), std::get<0>(key), std::get<1>(key), area});
    }
    out.displacements.resize(s_.meshes.size());
    std::sort(moves_.begin(), moves_.end(),
              [](const Move& a, const Move& b) { return a.mesh < b.mesh; });
    for (std::size_t i = 0; i < moves_.size();) {
      const std::uint32_t mesh = moves_[i].mesh;
      std::size_t j = i;
      while (j < moves_.size() && moves_[j].mesh == mesh) ++j;
      const std::vector<std::uint32_t> canon = weld(mesh);
      for (std::size_t k = i; k < j; ++k) moves_[k].vertex = canon[moves_[k].vertex];
      std::sort(moves_.begin() + i, moves_.begin() + j,
                [](const Move& a, const Move& b) { return a.vertex < b.vertex; });
      auto& disp = out.displacements[mesh];
      disp.assign(canon.size(), dvec3(0.0));
      for (std::size_t k = i; k < j;) {
        std::size_t l = k;
        while (l < j && moves_[l].vertex == moves_[k].vertex) ++l;
        disp[moves_[k].vertex] = displacement(&moves_[k], &moves_[l]);
        k = l;
      }
      for (std::size_t v = 0; v < canon.size(); ++v) disp[v] = disp[canon[v]];
      i = j;
    }
    return out;
  }

  const Scene& s_;
  const std::vector<bool>& is_target_;
  SceneTriangles tris_;
  dvec3 magnitude_{0.0};
  double pad_m_ = 0.0;
  std::vector<int> level_;
  std::map<std::tuple<std::uint32_t, std::uint32_t, Coincidence::Kind>, double> found_;
  std::vector<Move> moves_;
};

std::string format_area(double area_m2) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", area_m2);
  return std::string(buf) + " m²";
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

}  // namespace

double ray_offset_bound_m(double magnitude_m) {
  int e = 0;
  std::frexp(std::max(magnitude_m, 1e-30), &e);  // magnitude < 2^e: float ULP there <= 2^(e-24)
  return std::max(1.0 / 65536.0, 256.0 * std::ldexp(1.0, e - 24));
}

CoincidentGeometry find_coincident(const Scene& scene, const glm::dvec3& origin,
                                   const std::vector<bool>& is_target,
                                   const std::vector<bool>& movable) {
  bool any_target = false, mixed_materials = false;
  int material = -1;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (movable[m]) continue;
    any_target = any_target || is_target[m];
    mixed_materials = mixed_materials || (material >= 0 && scene.meshes[m].material != material);
    material = scene.meshes[m].material;
  }
  if (!any_target && !mixed_materials) {  // nothing that could matter: skip the grid
    return {{}, std::vector<std::vector<glm::dvec3>>(scene.meshes.size())};
  }
  return Detector(scene, origin, is_target, movable).run();
}

Warnings coincidence_warnings(const Scene& scene, const std::vector<Coincidence>& pairs) {
  Warnings out;
  for (const Coincidence& c : pairs) {
    const Mesh &a = scene.meshes[c.a], &b = scene.meshes[c.b];
    const std::string area = format_area(c.area_m2);
    switch (c.kind) {
      case Coincidence::Kind::TargetOnSurface:
        out.push_back("target mesh " + quoted(a.name) + " lies on mesh " + quoted(b.name) +
                      " (coplanar, overlapping over " + area +
                      "): light arriving from the target's front is counted on the target");
        break;
      case Coincidence::Kind::TargetsResolved:
        out.push_back("target meshes " + quoted(a.name) + " and " + quoted(b.name) +
                      " lie back to back (coplanar, overlapping over " + area +
                      "): each counts the light arriving at its own front");
        break;
      case Coincidence::Kind::TargetsArbitrary:
        out.push_back("target meshes " + quoted(a.name) + " and " + quoted(b.name) +
                      " overlap in one plane facing the same way over " + area +
                      ": the share of the light each receives there is arbitrary");
        break;
      case Coincidence::Kind::Materials:
        out.push_back(
            "meshes " + quoted(a.name) + " (material " + quoted(scene.materials[a.material].name) +
            ") and " + quoted(b.name) + " (material " + quoted(scene.materials[b.material].name) +
            ") overlap in one plane over " + area + ": the material seen there is arbitrary");
        break;
    }
  }
  return out;
}

}  // namespace lightsolver::detail
