#pragma once
// The triangles of coincident-surface detection (coincident.cpp) and the exact test of one
// pair: coplanar within the tolerance and overlapping, by how much (Sutherland-Hodgman).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "lightsolver/scene.hpp"
#include "model/coincident.hpp"

namespace lightsolver::detail::coincident_triangles {

using glm::dvec2;
using glm::dvec3;

// Normals parallel or antiparallel within 0.01 rad; the plane distance test does the real work.
inline const double kCosMaxAngle = std::cos(0.01);
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
  std::array<dvec2, 24> v;  // a clip at most doubles the count, whatever rounding does
  int n = 0;
};

inline double cross2(const dvec2& a, const dvec2& b) { return a.x * b.y - a.y * b.x; }

inline double signed_area(const Polygon& p) {
  double twice = 0.0;
  for (int i = 0; i < p.n; ++i) twice += cross2(p.v[i], p.v[(i + 1) % p.n]);
  return 0.5 * twice;
}

// Keeps the part of `in` left of the directed line a -> b.
inline Polygon clip(const Polygon& in, const dvec2& a, const dvec2& b) {
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
inline double ray_offset_along(const dvec3& n, const dvec3& magnitude) {
  double h = 0.0;
  for (int i = 0; i < 3; ++i) h += std::abs(n[i]) * ray_offset_bound_m(magnitude[i]);
  return h;
}

// Area of t and o overlapping within the tolerance of t's plane, or 0. `tol_m` is the largest
// distance between the planes allowed anywhere in the overlap.
inline double coplanar_overlap_m2(const Triangle& t, const Triangle& o, double tol_m) {
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

}  // namespace lightsolver::detail::coincident_triangles
