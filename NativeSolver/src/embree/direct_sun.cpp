// Direct sunlight at points, per hour (lightsolver/direct_sun.hpp; docs/daylight.md, "Direct
// sun at points (for ASE)"): the sun's beam through the scene's openings, checked by shadow rays
// through its opaque meshes (the Occluder EN 17037's sunlight exposure uses).
#include "lightsolver/direct_sun.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>
#include <limits>
#include <string>

#include "embree/occluder.hpp"
#include "lightsolver/sky_patches.hpp"
#include "types/luminaire_rows.hpp"

namespace lightsolver {
namespace {

constexpr const char* kWhere = "direct_sun_lx";

[[noreturn]] void fail(const std::string& field, const std::string& what) {
  throw InputError(kWhere, field, what);
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string indexed(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

void check_glazing(const GlazingDefinition& g, const std::string& at) {
  auto in_unit = [&](const char* key, double v) {
    if (!(v > 0.0 && v <= 1.0)) {
      fail(at + "." + key, "must be more than 0 and at most 1, got " + std::to_string(v));
    }
  };
  in_unit("transmittance", g.transmittance);
  in_unit("frame_factor", g.frame_factor);
  in_unit("maintenance_factor", g.maintenance_factor);
  if (g.panes != 1 && g.panes != 2) {
    fail(at + ".panes", "must be 1 (single) or 2 (double glazing), got " + std::to_string(g.panes));
  }
}

void check_inputs(const std::vector<SunOpening>& openings, const std::vector<glm::dvec3>& points,
                  const std::vector<glm::dvec3>& normals, const std::vector<float>& direction,
                  const std::vector<float>& e_n) {
  if (normals.size() != points.size()) {
    fail("normals", "has " + std::to_string(normals.size()) + " entries for " +
                        std::to_string(points.size()) + " points (one unit normal per point)");
  }
  if (direction.size() != 3 * e_n.size()) {
    fail("sun_direction", "has " + std::to_string(direction.size()) + " floats for " +
                              std::to_string(e_n.size()) + " hours (3 per hour)");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) fail(indexed("points", i), "is not finite");
    const glm::dvec3& n = normals[i];
    if (!finite(n)) fail(indexed("normals", i), "is not finite");
    const double len = glm::length(n);
    if (len == 0.0) fail(indexed("normals", i), "is zero (a point needs its unit normal)");
    if (std::abs(len - 1.0) > 1e-6) {
      fail(indexed("normals", i),
           "must be a unit vector (its length is " + std::to_string(len) + ")");
    }
  }
  for (std::size_t h = 0; h < e_n.size(); ++h) {
    const float e = e_n[h];
    if (!(std::isfinite(e) && e >= 0.0f)) {
      fail(indexed("sun_direct_normal_lx", h),
           "must be finite and at least 0, got " + std::to_string(e));
    }
    const glm::dvec3 s(direction[3 * h], direction[3 * h + 1], direction[3 * h + 2]);
    if (!finite(s)) fail(indexed("sun_direction", h), "is not finite");
    const double len = glm::length(s);
    if (e > 0.0f && std::abs(len - 1.0) > 1e-4) {
      fail(indexed("sun_direction", h),
           "must be a unit vector where sun_direct_normal_lx is more than 0 (its length is " +
               std::to_string(len) + ")");
    }
  }
  for (std::size_t k = 0; k < openings.size(); ++k) {
    const SunOpening& o = openings[k];
    const std::string at = indexed("openings", k);
    if (!finite(o.corner) || !finite(o.edge1) || !finite(o.edge2)) fail(at, "is not finite");
    const double area = glm::length(glm::cross(o.edge1, o.edge2));
    if (!(area > 1e-12 * glm::length(o.edge1) * glm::length(o.edge2)) || !(area > 0.0)) {
      fail(at, "has zero area (edge1 and edge2 parallel or zero)");
    }
    if (o.glazing) check_glazing(*o.glazing, at + ".glazing");
  }
}

// One opening, ready for the ray test: the parallelogram's plane and its glazing.
struct PreparedOpening {
  glm::dvec3 corner, edge1, edge2;
  glm::dvec3 m;          // edge1 × edge2 (into the room for a portal)
  double inv_m2 = 0.0;   // 1 / |m|²
  double inv_len = 0.0;  // 1 / |m|
  bool two_sided = false;
  std::optional<GlazingDefinition> glazing;
};

PreparedOpening prepare(const SunOpening& o) {
  PreparedOpening p;
  p.corner = o.corner;
  p.edge1 = o.edge1;
  p.edge2 = o.edge2;
  p.m = glm::cross(o.edge1, o.edge2);
  p.inv_m2 = 1.0 / glm::dot(p.m, p.m);
  p.inv_len = std::sqrt(p.inv_m2);
  p.two_sided = o.two_sided;
  p.glazing = o.glazing;
  return p;
}

// Where the ray from `x` toward the sun `s` crosses opening `o`, if it passes the beam there:
// the distance along the ray (> 0), or a negative value.
double crossing(const PreparedOpening& o, const glm::dvec3& x, const glm::dvec3& s) {
  const double denom = glm::dot(o.m, s);
  // A portal passes light travelling along m, i.e. against s: m·s < 0. Parallel: no crossing.
  if (denom == 0.0 || (!o.two_sided && denom > 0.0)) return -1.0;
  const double t = glm::dot(o.m, o.corner - x) / denom;
  if (!(t > 0.0)) return -1.0;
  const glm::dvec3 r = x + t * s - o.corner;
  const double u = glm::dot(glm::cross(r, o.edge2), o.m) * o.inv_m2;
  const double v = glm::dot(glm::cross(o.edge1, r), o.m) * o.inv_m2;
  return (u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0) ? t : -1.0;
}

// τ × frame × maintenance of the beam along s through o, as the sun's flux takes it (1 for an
// open hole).
double transmittance(const PreparedOpening& o, const glm::dvec3& s) {
  if (!o.glazing) return 1.0;
  return detail::beam_glazing(o.glazing, std::abs(glm::dot(o.m, s)) * o.inv_len);
}

// The share of the beam reaching `x` toward `s`: 0 when blocked, τ of its opening otherwise.
double beam_share(const Occluder& occ, const std::vector<PreparedOpening>& openings,
                  const glm::dvec3& x, const glm::dvec3& s) {
  if (openings.empty()) return occ.unobstructed(x, s) ? 1.0 : 0.0;
  const PreparedOpening* best = nullptr;
  double t_best = std::numeric_limits<double>::infinity();
  for (const PreparedOpening& o : openings) {
    const double t = crossing(o, x, s);
    if (t > 0.0 && t < t_best) {
      t_best = t;
      best = &o;
    }
  }
  if (!best) return 0.0;
  // The room's side up to the opening (stopping short of its plane, so that the wall it is cut
  // in does not block at the hole's edge), then the outside from just past it: the photons' own
  // tests (their travel from the opening, and opening_escape_origin's way out).
  const glm::dvec3 at = x + t_best * s;
  const double skip = Occluder::start_offset(at);
  if (!occ.unobstructed(x, s, t_best - skip)) return 0.0;
  if (!occ.unobstructed(at, s)) return 0.0;
  return transmittance(*best, s);
}

}  // namespace

std::vector<SunOpening> sun_openings(const Scene& scene) {
  auto portals = [](const SkyDefinition& sky) {
    std::vector<SunOpening> out;
    for (const SkyDefinition::Portal& p : sky.portals) {
      out.push_back({p.corner, p.edge1, p.edge2, p.glazing, false});
    }
    return out;
  };
  for (const Luminaire& l : scene.luminaires) {
    if (l.type != Luminaire::Type::Sun) continue;
    if (!l.sky.portals.empty()) return portals(l.sky);
    return {{l.corner, l.edge1, l.edge2, l.glazing, true}};
  }
  for (const Luminaire& l : scene.luminaires) {
    if (l.type == Luminaire::Type::Sky && !l.sky.portals.empty()) return portals(l.sky);
  }
  return {};
}

std::vector<float> direct_sun_lx(const Scene& scene, const std::vector<SunOpening>& openings,
                                 const std::vector<glm::dvec3>& points,
                                 const std::vector<glm::dvec3>& normals,
                                 const std::vector<float>& sun_direction,
                                 const std::vector<float>& sun_direct_normal_lx) {
  check_inputs(openings, points, normals, sun_direction, sun_direct_normal_lx);
  const std::size_t n_points = points.size();
  std::vector<float> out(sun_direct_normal_lx.size() * n_points, 0.0f);
  // Only the hours the sun lights: E_n > 0 and above the horizon.
  std::vector<std::size_t> lit;
  for (std::size_t h = 0; h < sun_direct_normal_lx.size(); ++h) {
    if (sun_direct_normal_lx[h] > 0.0f && sun_direction[3 * h + 2] > 0.0f) lit.push_back(h);
  }
  if (lit.empty() || n_points == 0) return out;
  std::vector<PreparedOpening> prepared;
  for (const SunOpening& o : openings) prepared.push_back(prepare(o));
  const Occluder occluder(scene);
  // Each (hour, point) is its own task writing its own entry: the result is the same for any
  // thread count and any split.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, lit.size() * n_points, 256),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::size_t h = lit[i / n_points], p = i % n_points;
          // Normalised in double: a float unit vector is unit to ~6·10⁻⁸.
          const glm::dvec3 s = glm::normalize(
              glm::dvec3(sun_direction[3 * h], sun_direction[3 * h + 1], sun_direction[3 * h + 2]));
          const double cos_n = glm::dot(normals[p], s);
          if (!(cos_n > 0.0)) continue;
          const double share = beam_share(occluder, prepared, points[p], s);
          out[h * n_points + p] = static_cast<float>(sun_direct_normal_lx[h] * cos_n * share);
        }
      });
  return out;
}

std::vector<float> direct_sun_lx(const Scene& scene, const std::vector<SunOpening>& openings,
                                 const std::vector<glm::dvec3>& points,
                                 const std::vector<glm::dvec3>& normals, const SkyMatrix& sky) {
  return direct_sun_lx(scene, openings, points, normals, sky.sun_direction,
                       sky.sun_direct_normal_lx);
}

}  // namespace lightsolver
