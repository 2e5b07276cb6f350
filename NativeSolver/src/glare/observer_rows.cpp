// The observer rows' result hooks (observer_rows.hpp), moved out of core's target_types.cpp so
// that core never includes glare.
#include "glare/observer_rows.hpp"

#include <stdexcept>

#include "glare/observer_grid.hpp"
#include "glare/observer_target.hpp"

namespace lightsolver::detail {

void observer_result(const TargetTallies& tt, TargetResult& r) {
  r.is_observer = true;
  if (tt.luminaires != nullptr) r.glare = observer_glare(tt.target, *tt.luminaires, r.estimate);
}

// Point k's tallies are its whole square's bin (the target's layout record, prepare's order).
void observer_grid_result(const TargetTallies& tt, TargetResult& r) {
  const PreparedTarget& at = tt.layout;
  const ObserverGridTallies points{
      [&tt, &at](std::size_t k) { return tt.estimate(at.point_bin(std::uint32_t(k))); },
      [&tt, &at](std::size_t k, double z) {
        return tt.estimate_z(at.point_bin(std::uint32_t(k)), z);
      }};
  if (tt.observer_grid == nullptr && tt.luminaires == nullptr) {
    throw std::logic_error("an observer grid's result needs the scene's luminaires");
  }
  // Traced: the geometry from the scene's luminaires; rescaled: from the results, dimmed.
  ObserverGridOutcome o = observer_grid_glare(
      tt.target.name,
      tt.observer_grid ? *tt.observer_grid : observer_grid_geometry(tt.target, *tt.luminaires),
      tt.confidence, points);
  r.estimate = points.estimate(o.estimate_point);
  r.glare = std::move(o.max);
  r.observer_grid = std::move(o.grid);
}

}  // namespace lightsolver::detail
