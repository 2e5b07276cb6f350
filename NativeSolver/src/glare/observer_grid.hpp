#pragma once
// An observer grid's glare (docs/glare.md, "Observer grids"): UGR at every (position, view
// direction) from its traced background luminance, and the largest UGR with an interval that
// holds for the maximum over all of them, not only at the point where the estimate peaks.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// An observer grid's traced indirect illuminance per point k (k = position * directions +
/// direction), at the run's confidence and at a critical value z.
struct ObserverGridTallies {
  std::function<Estimate(std::size_t k)> estimate;
  std::function<Estimate(std::size_t k, double z)> estimate_z;
};

struct ObserverGridOutcome {
  ObserverGridGlare grid;
  /// The maximum: UGR, its simultaneous interval, and the L_b, luminaires and warnings of the
  /// point where it occurs (point 0 when no point has glare).
  ObserverGlare max;
  std::size_t estimate_point = 0;  ///< that point
};

/// An observer grid's eyes, lines of sight and every point's glare terms: from the scene
/// (observer_grid_geometry) or from results with contributions (rescale, dimmed).
struct ObserverGridGeometry {
  std::vector<glm::dvec3> positions, view_directions;
  GlareTerms terms;  ///< point k = position * view_directions.size() + direction
};

/// (a) The geometry of observer grid `t` (validated) for `luminaires`.
ObserverGridGeometry observer_grid_geometry(const Target& t,
                                            const std::vector<Luminaire>& luminaires);

/// (b) The glare of observer grid `name` from its geometry and its points' tallies.
ObserverGridOutcome observer_grid_glare(const std::string& name, ObserverGridGeometry geometry,
                                        double confidence, const ObserverGridTallies& tallies);

}  // namespace lightsolver::detail
