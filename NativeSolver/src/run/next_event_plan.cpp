// Next-event estimation of direct light for a run (docs/statistics.md, "Next-event
// estimation"): which groups get it (estimate/next_event.hpp), how finely their direct parts
// are sampled for the run, and the parts kept for the next run with the same seed.
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "estimate/next_event.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/statistics.hpp"
#include "prepare/scene_effects.hpp"
#include "run/simulation_state.hpp"

namespace lightsolver {

// Next-event estimation for this run (estimate/next_event.hpp): which groups, and their direct
// parts, kept for the next run with the same seed. The points are sized to the run: about one
// shadow ray per two photons (a shadow ray costs about a photon segment), at least the defaults;
// an accuracy goal refines them until no direct part's half-width passes half the goal.
void Simulation::plan_direct_light(const Results& r) {
  detail::PreparedScene& p = state_->prepared;
  // A sobol run shares these parts among its replicates (model/replicates.hpp).
  detail::plan_next_event(p, *state_->backend, r.next_event);
  if (!std::any_of(p.groups.begin(), p.groups.end(),
                   [](const detail::PreparedGroup& g) { return g.next_event; })) {
    return;
  }
  // auto, the default, never costs a run far more than its photons: the fewest points (every
  // cell's 32, every surface's 512) each send a ray to every luminaire of their group, which
  // for thousands of luminaires in one group would be billions of rays for a small run.
  constexpr double kAutoRaysPerPhoton = 4.0;
  const std::uint64_t fewest = detail::direct_ray_count(p, 1);
  if (r.next_event == "auto" && double(fewest) > kAutoRaysPerPhoton * double(r.photons_requested)) {
    detail::plan_next_event(p, *state_->backend, "off");
    p.next_event_off = "its direct light would take " + std::to_string(fewest) +
                       " shadow rays, more than 4 per photon of the run (\"on\" traces them)";
    return;
  }
  p.photons_reflect = detail::analyse_effects(p).has(detail::Effect::Interreflection);
  const auto wide = [&](const std::vector<detail::DirectPart>& parts) {
    if (!r.target_accuracy) return false;
    const double z = z_for_confidence(r.confidence), half_goal = 0.5 * *r.target_accuracy;
    return std::any_of(parts.begin(), parts.end(), [&](const detail::DirectPart& d) {
      return d.lux > 0.0 && z * std::sqrt(d.variance) > half_goal * d.lux;
    });
  };
  std::uint32_t scale = 1;
  if (!r.target_accuracy && !r.decide) {
    const double rays = double(detail::direct_ray_count(p, 1));
    const double fit = rays > 0.0 ? std::sqrt(0.5 * double(r.photons_requested) / rays) : 1.0;
    scale = static_cast<std::uint32_t>(std::clamp(fit, 1.0, 16.0));
  }
  if (state_->direct_seed == r.seed && state_->direct_strata_scale == scale) {
    if (!wide(state_->direct)) {
      p.direct = state_->direct;
      return;
    }
    scale *= 2;
  }
  tbb::task_arena arena(state_->threads > 0 ? state_->threads : tbb::task_arena::automatic);
  for (;; scale *= 2) {
    arena.execute([&] { p.direct = detail::direct_parts(p, *state_->backend, r.seed, scale); });
    if (scale >= 16 || !wide(p.direct)) break;
  }
  state_->direct = p.direct;
  state_->direct_seed = r.seed;
  state_->direct_strata_scale = scale;
}

}  // namespace lightsolver
