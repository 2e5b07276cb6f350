// An observer grid's UGR per point and its maximum with a simultaneous interval (docs/glare.md,
// "Observer grids"; the same reasoning as Emax in docs/statistics.md, "Emin over noisy cells").
#include "glare/observer_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "types/target_types.hpp"
#include "glare/glare_terms.hpp"

namespace lightsolver::detail {
namespace {

// Bounds of max_k UGR_k with each side missing with probability at most alpha / 2. UGR_k falls
// as L_b,k rises.
//  - Upper: max_k UGR_k <= max_k UGR_k(L_b,k low) needs only the (fixed, unknown) arg-max point
//    j's L_b above its lower bound: one point's one-sided alpha / 2, the points' own intervals.
//  - Lower: max_k UGR_k(L_b,k high) <= max_k UGR_k fails when any point's L_b exceeds its
//    upper bound: a union over the m points, so each at one-sided alpha / (2 m) (Bonferroni,
//    whatever the correlation between points). A point whose upper bound is 0 gives no bound.
void max_bounds(const std::vector<ObserverGlare>& points, const std::vector<std::size_t>& glare,
                double confidence, const ObserverGridTallies& tallies, ObserverGlare& max) {
  max.ugr_ci_high = 0.0;
  for (const std::size_t k : glare) {
    if (!points[k].ugr_ci_high) {
      max.ugr_ci_high.reset();
      break;
    }
    max.ugr_ci_high = std::max(*max.ugr_ci_high, *points[k].ugr_ci_high);
  }
  const double z = z_for_alpha((1.0 - confidence) / double(glare.size()));
  max.ugr_ci_low.reset();
  for (const std::size_t k : glare) {
    const double lb_high = tallies.estimate_z(k, z).ci_high * (1.0 / std::numbers::pi);
    const std::optional<double> low = ugr_for(points[k].luminaire_sum, lb_high);
    if (low) max.ugr_ci_low = std::max(max.ugr_ci_low.value_or(*low), *low);
  }
  if (!max.ugr) return;  // unbounded: an interval open above holds it
  if (max.ugr_ci_low) max.ugr_ci_low = std::min(*max.ugr_ci_low, *max.ugr);
  if (max.ugr_ci_high) max.ugr_ci_high = std::max(*max.ugr_ci_high, *max.ugr);
}

// The point of the largest UGR: the first unbounded one (L_b = 0), else the largest estimate.
std::size_t arg_max(const std::vector<ObserverGlare>& points,
                    const std::vector<std::size_t>& glare) {
  std::size_t best = glare.front();
  for (const std::size_t k : glare) {
    if (!points[k].ugr) return k;
    if (*points[k].ugr > *points[best].ugr) best = k;
  }
  return best;
}

}  // namespace

ObserverGridGeometry observer_grid_geometry(const Target& t,
                                            const std::vector<Luminaire>& luminaires) {
  ObserverGridGeometry g;
  g.positions = observer_grid_positions(t);
  g.view_directions = observer_grid_directions(t);
  std::vector<GlareObserver> eyes;
  for (const glm::dvec3& position : g.positions) {
    for (const glm::dvec3& view : g.view_directions) eyes.push_back({position, view, t.up});
  }
  g.terms = glare_terms(luminaires, eyes);
  return g;
}

ObserverGridOutcome observer_grid_glare(const std::string& name, ObserverGridGeometry geometry,
                                        double confidence, const ObserverGridTallies& tallies) {
  ObserverGridOutcome out;
  out.grid.positions = std::move(geometry.positions);
  out.grid.view_directions = std::move(geometry.view_directions);
  std::vector<std::string> warnings;
  std::set<std::string> seen;
  std::vector<std::size_t> glare;  // the points where a luminaire counts
  for (std::size_t k = 0; k < geometry.terms.status.size(); ++k) {
    ObserverGlare g = eye_glare(name, geometry.terms, k, tallies.estimate(k));
    // "No luminaire counts" is said once for the grid below, not once per eye.
    if (!(g.luminaire_sum > 0.0) && !g.warnings.empty() &&
        g.warnings.back().find("no luminaire counts") != std::string::npos) {
      g.warnings.pop_back();
    }
    for (std::string& w : g.warnings) {
      if (seen.insert(w).second) warnings.push_back(std::move(w));
    }
    g.warnings.clear();
    if (g.luminaire_sum > 0.0) glare.push_back(k);
    out.grid.points.push_back(std::move(g));
  }
  if (!glare.empty()) out.estimate_point = arg_max(out.grid.points, glare);
  if (!glare.empty()) out.grid.max_at = out.estimate_point;
  // The maximum's point keeps its luminaires; the others' are dropped.
  out.max = out.grid.points.at(out.estimate_point);
  for (ObserverGlare& g : out.grid.points) g.contributions.clear();
  out.grid.terms = std::move(geometry.terms);
  const std::size_t eyes = out.grid.points.size();
  if (glare.empty()) {
    warnings.push_back(name + ": no luminaire counts toward UGR at any of its " +
                       std::to_string(eyes) +
                       " eyes (none in a field of view with a luminous area): no discomfort "
                       "glare from luminaires");
  } else if (glare.size() < eyes) {
    warnings.push_back(name + ": " + std::to_string(eyes - glare.size()) + " of its " +
                       std::to_string(eyes) +
                       " eyes (position x direction) have no rated luminaire in their field: "
                       "no glare there; the maximum is over the other " +
                       std::to_string(glare.size()));
  }
  out.max.warnings = std::move(warnings);
  if (glare.empty()) return out;
  max_bounds(out.grid.points, glare, confidence, tallies, out.max);
  return out;
}

}  // namespace lightsolver::detail
