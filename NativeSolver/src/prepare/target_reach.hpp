#pragma once
// Targets that cannot receive light, said before tracing. Only claimed when no surface returns
// light (every reflectance 0: direct light only), and only where geometry proves it: a photon
// lands on a target's front only if it starts in front of the target's plane and travels
// against the plane's normal, so a target is dark when, for every luminaire, every point the
// luminaire emits from lies behind the plane or every direction it emits in leaves the plane's
// front. Occlusion is ignored (it only darkens), and margins cover the tracer's float offsets.
#include <cstddef>
#include <string>
#include <vector>

#include "model/prepared_scene.hpp"
#include "prepare/scene_effects.hpp"

namespace lightsolver::detail {

struct DarkTarget {
  std::size_t target = 0;  ///< index into Scene::targets
  std::string message;     ///< "targets[2] (\"ceiling\"): ..."
};

/// The targets of `scene` (its prepared form `prepared`, analysed as `effects`) that cannot
/// receive light. Empty whenever some surface reflects. Movable target meshes are not judged
/// (they may be moved), nor targets too large to check quickly.
std::vector<DarkTarget> dark_targets(const Scene& scene, const PreparedScene& prepared,
                                     const SceneEffects& effects);

/// A run's hook: Results::effects (simulated and skipped) and a warning per dark target.
void report_effects(const Scene& scene, const PreparedScene& prepared, Results& results);

}  // namespace lightsolver::detail
