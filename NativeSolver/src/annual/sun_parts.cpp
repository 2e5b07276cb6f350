// The year's sun positions in bins and the sun's direct beam over grid cells (sun_parts.hpp).
#include "annual/sun_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <optional>

#include "lightsolver/direct_sun.hpp"
#include "types/luminaire_rows.hpp"

namespace lightsolver {

SunBins sun_bins(const SkyMatrix& y, int mf, double north_deg) {
  const SkyPatches patches(mf, north_deg);
  SunBins out;
  out.of_hour.assign(y.hours, -1);
  std::vector<int> bin_of_patch(patches.count(), -1);
  for (int h = 0; h < y.hours; ++h) {
    if (y.status[h] != 2 || !(y.sun_direct_normal_lx[h] > 0.0f)) continue;
    const float* d = &y.sun_direction[3 * std::size_t(h)];
    const glm::dvec3 s = glm::normalize(glm::dvec3(d[0], d[1], d[2]));
    int& b = bin_of_patch[patches.index(s)];
    if (b < 0) {
      b = static_cast<int>(out.direction.size());
      out.direction.emplace_back(0.0);
    }
    out.direction[b] += s;
    out.of_hour[h] = b;
  }
  for (glm::dvec3& v : out.direction) v = glm::normalize(v);
  return out;
}

namespace {

bool any_sun(const SkyMatrix& y) {
  return std::any_of(y.sun_direct_normal_lx.begin(), y.sun_direct_normal_lx.end(),
                     [](float e) { return e > 0.0f; });
}

using Quad = std::array<glm::dvec2, 4>;

// The grid's affine coordinates (a, b) of a point of its plane, each 0 … 1 over the grid.
struct GridFrame {
  glm::dvec3 corner, e1, e2, n;
  double g11, g12, g22, det;
  explicit GridFrame(const Target& t)
      : corner(t.corner),
        e1(t.edge1),
        e2(t.edge2),
        n(glm::normalize(glm::cross(t.edge1, t.edge2))) {
    g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2);
    det = g11 * g22 - g12 * g12;
  }
  glm::dvec2 ab(const glm::dvec3& p) const {
    const glm::dvec3 r = p - corner;
    const double x = glm::dot(r, e1), y = glm::dot(r, e2);
    return {(g22 * x - g12 * y) / det, (g11 * y - g12 * x) / det};
  }
};

// An opening's beam on the grid's plane: its corners carried along the beam (travel −s), in
// (a, b). None where the beam does not pass it or a corner does not lie in front of the plane.
std::optional<Quad> beam_on_plane(const SunOpening& o, const glm::dvec3& s, const GridFrame& f) {
  const glm::dvec3 d = -s;
  const glm::dvec3 n_in = glm::normalize(glm::cross(o.edge1, o.edge2));
  if (!o.two_sided && !(glm::dot(d, n_in) > 0.0)) return std::nullopt;
  const double dn = glm::dot(d, f.n);
  if (!(dn < 0.0)) return std::nullopt;  // the beam runs away from the grid's lit side
  const glm::dvec3 c[4] = {o.corner, o.corner + o.edge1, o.corner + o.edge1 + o.edge2,
                           o.corner + o.edge2};
  Quad q;
  for (int i = 0; i < 4; ++i) {
    const double t = glm::dot(f.corner - c[i], f.n) / dn;
    if (!(t >= 0.0)) return std::nullopt;  // part of the opening behind the plane: rays judge
    q[i] = f.ab(c[i] + t * d);
  }
  return q;
}

// Area of the convex quad q clipped to [a0, a1] × [b0, b1] (Sutherland–Hodgman, shoelace).
double clipped_area(const Quad& q, double a0, double a1, double b0, double b1) {
  std::vector<glm::dvec2> poly(q.begin(), q.end()), next;
  auto clip = [&](int axis, double bound, bool keep_above) {
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const glm::dvec2 p = poly[i], r = poly[(i + 1) % poly.size()];
      const bool pin = keep_above ? p[axis] >= bound : p[axis] <= bound;
      const bool rin = keep_above ? r[axis] >= bound : r[axis] <= bound;
      if (pin) next.push_back(p);
      if (pin != rin) {
        const double t = (bound - p[axis]) / (r[axis] - p[axis]);
        next.push_back(p + t * (r - p));
      }
    }
    poly.swap(next);
  };
  clip(0, a0, true);
  clip(0, a1, false);
  clip(1, b0, true);
  clip(1, b1, false);
  double twice = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec2 p = poly[i], r = poly[(i + 1) % poly.size()];
    twice += p.x * r.y - r.x * p.y;
  }
  return 0.5 * std::abs(twice);
}

// Inside the convex quad (either winding), or within `eps` of its edge (-1: undecided).
int inside(const Quad& q, const glm::dvec2& p, double eps) {
  bool pos = false, neg = false, near = false;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec2 e = q[(i + 1) % 4] - q[i], r = p - q[i];
    const double len = std::max(glm::length(e), 1e-300);
    const double side = (e.x * r.y - e.y * r.x) / len;
    if (std::abs(side) < eps) near = true;
    (side > 0.0 ? pos : neg) = true;
  }
  if (near) return -1;
  return pos && neg ? 0 : 1;
}

// One hour's beams: each opening's quad on the plane and the illuminance it brings (E_n cos τ).
struct Beam {
  Quad quad;
  double lx;
};

std::vector<Beam> beams(const std::vector<SunOpening>& openings, const glm::dvec3& s, double en,
                        const GridFrame& f) {
  std::vector<Beam> out;
  for (const SunOpening& o : openings) {
    const std::optional<Quad> q = beam_on_plane(o, s, f);
    if (!q) continue;
    const glm::dvec3 n_in = glm::normalize(glm::cross(o.edge1, o.edge2));
    const double cos_i = std::abs(glm::dot(n_in, s));
    out.push_back({*q, en * glm::dot(f.n, s) * detail::beam_glazing(o.glazing, cos_i)});
  }
  return out;
}

// The value the rays should read at a point if only the openings shape the beam (-1: a point on
// a beam's edge, not judged).
double expected(const std::vector<Beam>& bs, const glm::dvec2& p) {
  double v = 0.0;
  for (const Beam& b : bs) {
    const int in = inside(b.quad, p, 1e-7);
    if (in < 0) return -1.0;
    if (in) v += b.lx;
  }
  return v;
}

}  // namespace

void direct_sun_cells(const Scene& scene, const Target& t, const SkyMatrix& y, int k,
                      CoefficientGrid& out) {
  if (!any_sun(y)) return;
  const std::vector<SunOpening> openings = sun_openings(scene);
  const GridFrame frame(t);
  const std::size_t nu = t.nu, nv = t.nv, cells = nu * nv, hours = std::size_t(y.hours);
  const std::size_t pu = nu * k + 1, pv = nv * k + 1;  // corner points, shared between cells
  for (auto* v : {&out.direct, &out.direct_low, &out.direct_high, &out.direct_centre}) {
    v->assign(hours * cells, 0.0f);
  }
  const double inv = 1.0 / (double(k) * k);
  // A band of one row of cells at a time: (k + 1) rows of corner points, plus the cells' centres
  // when k is odd, so that the hours × points array stays small.
  for (std::size_t iv = 0; iv < nv; ++iv) {
    std::vector<glm::dvec3> points;
    for (std::size_t j = iv * k; j <= (iv + 1) * std::size_t(k); ++j) {
      for (std::size_t i = 0; i < pu; ++i) {
        points.push_back(t.corner + double(i) / double(pu - 1) * t.edge1 +
                         double(j) / double(pv - 1) * t.edge2);
      }
    }
    const std::size_t corners = points.size();
    if (k % 2 != 0) {
      for (std::size_t iu = 0; iu < nu; ++iu) {
        points.push_back(t.corner + (iu + 0.5) / nu * t.edge1 + (iv + 0.5) / nv * t.edge2);
      }
    }
    const std::vector<glm::dvec3> normals(points.size(), frame.n);
    const std::vector<float> e = direct_sun_lx(scene, openings, points, normals, y);
    const std::size_t np = points.size();
    for (std::size_t h = 0; h < hours; ++h) {
      if (!(y.sun_direct_normal_lx[h] > 0.0f)) continue;
      const float* sd = &y.sun_direction[3 * h];
      const glm::dvec3 s = glm::normalize(glm::dvec3(sd[0], sd[1], sd[2]));
      const std::vector<Beam> bs = beams(openings, s, y.sun_direct_normal_lx[h], frame);
      const float* row = &e[h * np];
      for (std::size_t iu = 0; iu < nu; ++iu) {
        double mean = 0.0, lo = 0.0, hi = 0.0;
        bool shaped_by_openings = !openings.empty();
        for (int b = 0; b <= k; ++b) {  // every corner as the openings alone would light it
          for (int a = 0; a <= k && shaped_by_openings; ++a) {
            const std::size_t i = iu * k + a;
            const glm::dvec2 p(double(i) / double(pu - 1), double(iv * k + b) / double(pv - 1));
            const double want = expected(bs, p), got = row[std::size_t(b) * pu + i];
            if (want >= 0.0 && std::abs(got - want) > 1e-4 * std::max(1.0, want))
              shaped_by_openings = false;
          }
        }
        for (int b = 0; b < k; ++b) {
          for (int a = 0; a < k; ++a) {
            const std::size_t i = iu * k + a, j = b;
            const float c[4] = {row[j * pu + i], row[j * pu + i + 1], row[(j + 1) * pu + i],
                                row[(j + 1) * pu + i + 1]};
            mean += 0.25 * (double(c[0]) + c[1] + c[2] + c[3]);
            lo += *std::min_element(c, c + 4);
            hi += *std::max_element(c, c + 4);
          }
        }
        mean *= inv, lo *= inv, hi *= inv;
        if (shaped_by_openings) {  // the beams' exact areas over the cell
          const double a0 = double(iu) / nu, a1 = double(iu + 1) / nu;
          const double b0 = double(iv) / nv, b1 = double(iv + 1) / nv;
          mean = 0.0;
          for (const Beam& bm : bs) {
            mean += bm.lx * clipped_area(bm.quad, a0, a1, b0, b1) / ((a1 - a0) * (b1 - b0));
          }
          lo = hi = mean;
        }
        const std::size_t at = h * cells + iv * nu + iu;
        out.direct[at] = static_cast<float>(mean);
        out.direct_low[at] = std::min(out.direct[at], static_cast<float>(lo));
        out.direct_high[at] = std::max(out.direct[at], static_cast<float>(hi));
        out.direct_centre[at] = k % 2 == 0
                                    ? row[std::size_t(k / 2) * pu + iu * k + std::size_t(k / 2)]
                                    : row[corners + iu];
      }
    }
  }
}

}  // namespace lightsolver
