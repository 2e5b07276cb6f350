#include "optimizer/placement_region.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "types/luminaire_types.hpp"

namespace lightsolver::optimizer::regions {
namespace {

// Twice the signed area (shoelace).
double twice_area(const std::vector<glm::dvec2>& poly) {
  double a = 0.0;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    a += poly[j].x * poly[i].y - poly[i].x * poly[j].y;
  }
  return a;
}

glm::dvec2 cell_centre(const SceneVariable& v, const Domain& d, const Configuration& c) {
  return {d.variables()[v.first].value(c[v.first]),
          d.variables()[v.first + 1].value(c[v.first + 1])};
}

}  // namespace

PlacementRegion read_region(const lightsolver::detail::JsonNode& within, const SceneVariable& v,
                            const Domain& domain) {
  // Dual basis of (edge1, edge2) in their plane: (u, v) of p = corner + u e1 + v e2 + w n.
  const glm::dvec3 n = glm::cross(v.edge1, v.edge2);
  const glm::dvec3 du = glm::cross(v.edge2, n) / glm::dot(v.edge1, glm::cross(v.edge2, n));
  const glm::dvec3 dv = glm::cross(n, v.edge1) / glm::dot(v.edge2, glm::cross(n, v.edge1));
  auto ring = [&](const lightsolver::detail::JsonNode& points) {
    std::vector<glm::dvec2> poly;
    for (std::size_t i = 0; i < points.array_size(); ++i) {
      const glm::dvec3 rel = points[i].vec3() - v.corner;
      poly.emplace_back(glm::dot(rel, du), glm::dot(rel, dv));
    }
    if (poly.size() < 3) points.fail("a polygon needs at least 3 points");
    if (!(std::abs(twice_area(poly)) > 1e-12)) {
      points.fail("the polygon has no area in the plane of edge1 and edge2");
    }
    return poly;
  };
  PlacementRegion region;
  if (within.has("outer") || within.has("holes")) {
    within.require_object({"outer", "holes"});
    region.push_back(ring(within.at("outer")));
    if (within.has("holes")) {
      const lightsolver::detail::JsonNode holes = within.at("holes");
      for (std::size_t i = 0; i < holes.array_size(); ++i) region.push_back(ring(holes[i]));
    }
  } else {
    region.push_back(ring(within));
  }
  const auto& u = domain.variables()[v.first];
  const auto& w = domain.variables()[v.first + 1];
  for (std::uint32_t i = 0; i < u.size(); ++i) {
    for (std::uint32_t j = 0; j < w.size(); ++j) {
      if (inside(region, {u.value(i), w.value(j)})) return region;
    }
  }
  within.fail("no cell centre of the rectangle lies inside the region (refine cells?)");
}

bool inside(const PlacementRegion& region, glm::dvec2 q) {
  bool in = false;
  for (const std::vector<glm::dvec2>& polygon : region) {
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
      const glm::dvec2 a = polygon[i], b = polygon[j];
      if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y)) {
        in = !in;
      }
    }
  }
  return in;
}

std::function<bool(const Configuration&)> admissible_filter(const SceneProblem& p) {
  std::vector<SceneVariable> regional;
  for (const SceneVariable& v : p.variables) {
    if (!v.region.empty()) regional.push_back(v);
  }
  if (regional.empty()) return {};
  return [regional, domain = p.domain](const Configuration& c) {
    for (const SceneVariable& v : regional) {
      if (!inside(v.region, cell_centre(v, domain, c))) return false;
    }
    return true;
  };
}

namespace {

// Where a luminaire "is" for placement: its position, or the centre of its parallelogram (as
// the scene evaluator's anchor).
glm::dvec3 anchor(const Luminaire& l) { return detail::luminaire_type(l.type).centre(l); }

struct Mover {
  std::size_t first;          // the variable's u; v is first + 1
  glm::dvec3 corner, e1, e2;  // its rectangle
  std::vector<glm::dvec3> offsets;
};

}  // namespace

std::function<bool(const Configuration&)> spacing_filter(const SceneProblem& p) {
  std::vector<Mover> movers;
  std::vector<bool> moved(p.scene.luminaires.size(), false);
  for (const SceneVariable& v : p.variables) {
    if (v.type != SceneVariable::Type::kPosition) continue;
    movers.push_back({v.first, v.corner, v.edge1, v.edge2, v.offsets});
    for (std::size_t i : v.luminaires) moved[i] = true;
  }
  std::vector<glm::dvec3> fixed;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const Luminaire& l = p.scene.luminaires[i];
    if (!moved[i] && detail::luminaire_type(l.type).placed) fixed.push_back(anchor(l));
  }
  if (movers.empty() || (movers.size() == 1 && fixed.empty())) return {};
  const double min2 = std::pow(std::max(p.min_spacing_m, 1e-6), 2);
  return [movers, fixed, min2, domain = p.domain](const Configuration& c) {
    std::vector<std::pair<std::size_t, glm::dvec3>> placed;  // (mover, anchor)
    for (std::size_t k = 0; k < movers.size(); ++k) {
      const Mover& m = movers[k];
      const glm::dvec3 at = m.corner + domain.variables()[m.first].value(c[m.first]) * m.e1 +
                            domain.variables()[m.first + 1].value(c[m.first + 1]) * m.e2;
      for (const glm::dvec3& o : m.offsets) {
        const glm::dvec3 q = at + o;
        for (const glm::dvec3& f : fixed) {
          const glm::dvec3 d = q - f;
          if (glm::dot(d, d) < min2) return false;
        }
        for (const auto& [other, r] : placed) {
          const glm::dvec3 d = q - r;
          if (other != k && glm::dot(d, d) < min2) return false;
        }
        placed.emplace_back(k, q);
      }
    }
    return true;
  };
}

std::function<bool(const Configuration&)> both(std::function<bool(const Configuration&)> a,
                                               std::function<bool(const Configuration&)> b) {
  if (!a) return b;
  if (!b) return a;
  return [a = std::move(a), b = std::move(b)](const Configuration& c) { return a(c) && b(c); };
}

}  // namespace lightsolver::optimizer::regions
