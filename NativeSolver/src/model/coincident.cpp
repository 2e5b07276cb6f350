#include "model/coincident.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>
#include <map>
#include <tuple>
#include <unordered_map>

#include "lightsolver/timings.hpp"
#include "model/coincident_grid.hpp"
#include "model/coincident_planes.hpp"
#include "model/coincident_triangles.hpp"

namespace lightsolver::detail {
namespace {

using coincident_grid::Entry;
using coincident_grid::for_each_cell;
using coincident_grid::Grid;
using coincident_grid::kLevelBias;
using coincident_grid::level_of;

using coincident_triangles::coplanar_overlap_m2;
using coincident_triangles::kCosMaxAngle;
using coincident_triangles::ray_offset_along;
using coincident_triangles::SceneTriangles;
using coincident_triangles::Triangle;

using glm::dvec3;

// Detection tolerance = 2 x the tracer's ray offset; the hidden triangle moves by 2 x that.
constexpr double kToleranceMargin = 2.0, kMoveFactor = 2.0;

// --- the rule ---------------------------------------------------------------------------------

struct Hit {
  std::size_t gt, go;  // global triangles: the reference (target) one, the other
  double area_m2, move_m;
  bool operator<(const Hit& o) const { return std::tie(gt, go) < std::tie(o.gt, o.go); }
};

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
    std::vector<coincident_planes::Plane> planes;
    {
      const timings::Scope phase("planes");
      planes = planes_and_magnitude();
    }
    const timings::Scope phase("plane filter");
    const std::vector<std::uint8_t> keep = plane_filter(planes);
    for (std::size_t g = 0; g < keep.size(); ++g) {
      if (keep[g]) kept_.push_back(static_cast<std::uint32_t>(g));
    }
  }

  CoincidentGeometry run() {
    std::vector<Hit> hits = coplanar_hits();
    const timings::Scope phase("the rule");
    // Sorted, the rule sees the pairs in one order whatever the threads did: sums are exact
    // repeats from run to run.
    std::sort(hits.begin(), hits.end());
    for (const Hit& h : hits) apply_rule(h);
    return finish();
  }

 private:
  // Every coplanar overlapping pair among the triangles the plane filter kept, in any order.
  // The grid numbers them k = 0, 1, ... in the order of their global index kept_[k].
  std::vector<Hit> coplanar_hits() {
    const timings::Scope phase("grid");
    const std::size_t n = kept_.size();
    kept_boxes();
    std::vector<Entry> entries;
    entries.reserve(2 * n);
    level_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      level_[k] = level_of(lo_[k], hi_[k]);
      for_each_cell(level_[k], lo_[k], hi_[k], [&](std::uint64_t key) {
        entries.push_back({key, mesh(k), static_cast<std::uint32_t>(k)});
      });
    }
    const std::vector<std::uint64_t> partner_levels = levels_of_partners();
    const Grid grid(std::move(entries));
    struct Local {
      std::vector<std::uint32_t> seen;  // stamps: k + 1 of the last triangle that met it
      std::vector<Hit> hits;
    };
    tbb::enumerable_thread_specific<Local> locals;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
      Local& local = locals.local();
      local.seen.resize(n, 0);
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        const std::uint64_t levels = partner_levels[mesh(k)] >> (level_[k] + kLevelBias);
        if (levels == 0) continue;
        for (int l = 0; l < 64 - level_[k] - kLevelBias; ++l) {
          if (!(levels >> l & 1)) continue;
          for_each_cell(level_[k] + l, lo_[k], hi_[k], [&](std::uint64_t key) {
            visit_cell(grid, key, k, local.seen, local.hits);
          });
        }
      }
    });
    std::vector<Hit> hits;
    for (const Local& local : locals) hits.insert(hits.end(), local.hits.begin(), local.hits.end());
    return hits;
  }

  std::uint32_t mesh(std::size_t k) const { return tris_.mesh(kept_[k]); }

  static std::vector<bool> included(const Scene& s, const std::vector<bool>& movable) {
    std::vector<bool> in(s.meshes.size());
    for (std::size_t m = 0; m < in.size(); ++m) in[m] = !movable[m];
    return in;
  }

  // Per mesh, the grid levels holding triangles of meshes it is relevant with (bit l: level
  // l - kLevelBias): a triangle looks only there, so a million triangles of one material
  // around a few of another cost a few lookups each.
  std::vector<std::uint64_t> levels_of_partners() const {
    const std::size_t n = s_.meshes.size();
    std::vector<std::uint64_t> own(n, 0);
    for (std::size_t k = 0; k < kept_.size(); ++k) own[mesh(k)] |= 1ull << (level_[k] + kLevelBias);
    std::vector<std::array<int, 64>> by_material(s_.materials.size(), std::array<int, 64>{});
    std::array<int, 64> all{}, targets{}, others{};
    for (std::size_t m = 0; m < n; ++m) {
      for (int b = 0; b < 64; ++b) {
        const int has = own[m] >> b & 1;
        all[b] += has;
        (is_target_[m] ? targets : others)[b] += has;
        if (!is_target_[m]) by_material[s_.meshes[m].material][b] += has;
      }
    }
    std::vector<std::uint64_t> out(n, 0);
    for (std::size_t m = 0; m < n; ++m) {
      for (int b = 0; b < 64; ++b) {
        const int has = own[m] >> b & 1;
        const bool any =
            is_target_[m] ? all[b] - has > 0
                          : targets[b] > 0 || others[b] - by_material[s_.meshes[m].material][b] > 0;
        if (any) out[m] |= 1ull << b;
      }
    }
    return out;
  }

  // Each triangle's plane, and magnitude_ and pad_m_, in one parallel pass (a maximum is exact
  // in any order).
  std::vector<coincident_planes::Plane> planes_and_magnitude() {
    std::vector<coincident_planes::Plane> planes(tris_.size());
    magnitude_ = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, tris_.size(), 4096), dvec3(0.0),
        [&](const auto& r, dvec3 m) {
          for (std::size_t g = r.begin(); g != r.end(); ++g) {
            const Triangle t = tris_.get(g);
            for (const dvec3& p : t.p) m = glm::max(m, glm::abs(p));
            planes[g] = {t.n, glm::dot(t.n, t.p[0])};
          }
          return m;
        },
        [](const dvec3& a, const dvec3& b) { return glm::max(a, b); });
    // Boxes grow by the largest tolerance anywhere, so no coplanar pair is missed.
    pad_m_ = kToleranceMargin * ray_offset_along(dvec3(1.0), magnitude_);
    return planes;
  }

  // The padded box of each triangle the plane filter kept.
  void kept_boxes() {
    lo_.resize(kept_.size());
    hi_.resize(kept_.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kept_.size(), 4096), [&](const auto& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) {
        tris_.bounds(kept_[k], lo_[k], hi_[k]);
        lo_[k] -= pad_m_;
        hi_[k] += pad_m_;
      }
    });
  }

  // Per triangle, whether its plane comes near the plane of a triangle of a mesh it is
  // relevant with (coincident_planes.hpp): the others cannot be in any pair. The bounds hold
  // for every pair coplanar_overlap_m2 accepts, with a margin for rounding: normals within the
  // chord of 0.01 rad, and for a point q of the overlap (in t's plane, within tol_m <= pad_m_
  // of o's), |d_t - s d_o| <= |n_t - s n_o| |q| + tol_m, |q| at most |magnitude_|.
  std::vector<std::uint8_t> plane_filter(
      const std::vector<coincident_planes::Plane>& planes) const {
    const double chord = 2.0 * std::sin(0.5 * std::acos(kCosMaxAngle));
    const double normal_tol = 1.01 * chord + 1e-12;
    const double offset_tol = 1.01 * (normal_tol * glm::length(magnitude_) + pad_m_) + 1e-9;
    return coincident_planes::near_planes(
        planes, normal_tol, offset_tol, [&](std::size_t g) { return tris_.mesh(g); },
        [&](std::uint32_t m) { return bool(is_target_[m]); },
        [&](std::uint32_t m) { return static_cast<std::int32_t>(s_.meshes[m].material); });
  }

  // Pairs that can matter: one side is a target, or the materials differ.
  bool relevant(std::uint32_t a, std::uint32_t b) const {
    return a != b &&
           (is_target_[a] || is_target_[b] || s_.meshes[a].material != s_.meshes[b].material);
  }

  // k: a kept triangle (coplanar_hits' numbering), as are the entries of the grid.
  void visit_cell(const Grid& grid, std::uint64_t key, std::size_t k,
                  std::vector<std::uint32_t>& seen, std::vector<Hit>& hits) const {
    const std::uint32_t own = mesh(k);
    auto [i, end] = grid.find(key);
    while (i < end) {
      const Entry& e = grid.entry(i);
      if (!relevant(own, e.mesh)) {
        i = grid.run_end(i);  // skip this mesh's entries in the cell at once
        continue;
      }
      ++i;
      // Same-level pairs are met from both sides: keep one. Stamps drop a cell's repeats.
      if ((level_[e.tri] == level_[k] && e.tri <= k) || seen[e.tri] == k + 1) continue;
      seen[e.tri] = static_cast<std::uint32_t>(k + 1);
      test_pair(k, e.tri, hits);
    }
  }

  // Boxes kept, not recomputed: a query tests the boxes of many partners.
  void test_pair(std::size_t k1, std::size_t k2, std::vector<Hit>& hits) const {
    if (glm::any(glm::lessThan(hi_[k1], lo_[k2])) || glm::any(glm::lessThan(hi_[k2], lo_[k1])))
      return;
    // The reference triangle t: the target's where there is one, else the lower mesh's.
    const std::size_t g1 = kept_[k1], g2 = kept_[k2];
    const std::uint32_t m1 = tris_.mesh(g1), m2 = tris_.mesh(g2);
    const bool t_first = is_target_[m1] != is_target_[m2] ? is_target_[m1] : m1 < m2;
    const std::size_t gt = t_first ? g1 : g2, go = t_first ? g2 : g1;
    const Triangle t = tris_.get(gt), o = tris_.get(go);
    dvec3 magnitude(0.0);
    for (const dvec3& p : t.p) magnitude = glm::max(magnitude, glm::abs(p));
    for (const dvec3& p : o.p) magnitude = glm::max(magnitude, glm::abs(p));
    const double tol_m = kToleranceMargin * ray_offset_along(t.n, magnitude);
    const double area = coplanar_overlap_m2(t, o, tol_m);
    if (area > 0.0) hits.push_back({gt, go, area, kMoveFactor * tol_m});
  }

  // Same-facing: the other triangle steps back behind the target (the lit side, with its grids
  // and flush luminaires, is untouched). Back to back: the smaller triangle steps toward its own
  // front, the side the other one hides, so the disturbance stays as local as possible.
  void apply_rule(const Hit& h) {
    const Triangle t = tris_.get(h.gt), o = tris_.get(h.go);
    const std::uint32_t mt = tris_.mesh(h.gt), mo = tris_.mesh(h.go);
    const bool same_facing = glm::dot(t.n, o.n) > 0.0;
    using K = Coincidence::Kind;
    if (!is_target_[mt]) {
      // Two closed bodies touching face to face (a wall standing on a slab, a desk on the
      // floor, a pane in its frame): the shared patch lies inside them, where no light from
      // the room arrives, so nothing is arbitrary. Otherwise (open sheets back to back, or
      // one surface over another facing the same way) tracing is double-sided and nothing
      // moves: from either side either material is seen.
      const bool contact = !same_facing && closed(mt) && closed(mo);
      found_[{mt, mo, contact ? K::Contact : K::Materials}] += h.area_m2;
    } else if (is_target_[mo] && same_facing) {
      found_[{mt, mo, K::TargetsArbitrary}] += h.area_m2;
    } else {
      const K kind = !same_facing ? K::Contact : K::TargetOnSurface;
      found_[{mt, mo, kind}] += h.area_m2;
      if (same_facing || o.area_m2 < t.area_m2) {
        add_move(h.go, -t.n, h.move_m);
      } else {
        add_move(h.gt, t.n, h.move_m);
      }
    }
  }

  // Whether the mesh is part of a closed surface: with the vertices of all meshes welded by
  // position, every edge of its triangles is shared by an even number of triangles of the
  // scene. Counted over all meshes because the export splits one body into several (a slab's
  // top, bottom and sides carry different materials; a target face is cut out of its wall).
  // Called in apply_rule only, which runs on one thread; the counts are made once, when the
  // first such pair asks.
  bool closed(std::uint32_t mesh) {
    if (edge_ids_.empty()) count_edges();
    for (const auto& t : s_.meshes[mesh].triangles) {
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t key = edge_key(edge_ids_[mesh][t[k]], edge_ids_[mesh][t[(k + 1) % 3]]);
        if (key != kNoEdge && edge_count_.at(key) % 2 != 0) return false;
      }
    }
    return !s_.meshes[mesh].triangles.empty();
  }

  static constexpr std::uint64_t kNoEdge = ~std::uint64_t(0);

  static std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    if (a == b) return kNoEdge;  // a degenerate edge
    if (b < a) std::swap(a, b);
    return std::uint64_t(a) << 32 | b;
  }

  void count_edges() {
    std::map<std::tuple<double, double, double>, std::uint32_t> ids;
    edge_ids_.resize(s_.meshes.size());
    for (std::size_t m = 0; m < s_.meshes.size(); ++m) {
      for (const dvec3& v : s_.meshes[m].vertices) {
        const auto id = static_cast<std::uint32_t>(ids.size());
        edge_ids_[m].push_back(ids.emplace(std::tuple(v.x, v.y, v.z), id).first->second);
      }
      for (const auto& t : s_.meshes[m].triangles) {
        for (int k = 0; k < 3; ++k) {
          const std::uint64_t key = edge_key(edge_ids_[m][t[k]], edge_ids_[m][t[(k + 1) % 3]]);
          if (key != kNoEdge) ++edge_count_[key];
        }
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
        // data() + l, not &moves_[l]: l may be one past the end.
        disp[moves_[k].vertex] = displacement(moves_.data() + k, moves_.data() + l);
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
  std::vector<std::uint32_t> kept_;  // the triangles the plane filter kept, ascending
  std::vector<dvec3> lo_, hi_;       // per kept triangle, its box grown by pad_m_
  std::vector<int> level_;           // per kept triangle, its grid level
  std::map<std::tuple<std::uint32_t, std::uint32_t, Coincidence::Kind>, double> found_;
  std::vector<Move> moves_;
  std::vector<std::vector<std::uint32_t>> edge_ids_;  // closed(): per mesh, welded vertex ids
  std::unordered_map<std::uint64_t, std::uint32_t> edge_count_;  // triangles per welded edge
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
      case Coincidence::Kind::Contact:  // an object standing on a surface: nothing to say
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
