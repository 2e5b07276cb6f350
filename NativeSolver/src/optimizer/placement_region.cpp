#include "optimizer/placement_region.hpp"

#include <glm/geometric.hpp>

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

}  // namespace lightsolver::optimizer::regions
