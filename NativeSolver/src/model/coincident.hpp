#pragma once
// Coincident surfaces (docs/solver.md, "Coincident surfaces"): triangles of two meshes lying in
// one plane, within the tracer's robustness tolerance, and overlapping. A ray tracer returns
// whichever of two coplanar triangles it meets first, so a target lying on another surface
// would get an arbitrary share of the light arriving there. Prepare detects such pairs, moves
// the hidden triangle out of the way by four ray offsets (float ULPs at its coordinates) so the
// target is met first on every backend, and reports what it found.
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

/// Two meshes with coplanar, overlapping triangles, and the overlapping area.
struct Coincidence {
  enum class Kind {
    TargetOnSurface,  ///< `a` is a target mesh, `b` is not: the target gets the light
    /// back to back, at least one a target (furniture standing on a floor target): each side
    /// keeps the light arriving at its own front; or two closed non-target meshes touching
    /// face to face (a wall on a slab): the patch lies inside them. Nothing is arbitrary,
    /// so it is not warned
    Contact,
    TargetsArbitrary,  ///< two target meshes facing the same way: the share is arbitrary
    Materials,         ///< two non-target meshes with different materials: arbitrary material
  };
  Kind kind = Kind::TargetOnSurface;
  std::size_t a = 0, b = 0;  ///< mesh indices (a < b unless a is the target of TargetOnSurface)
  double area_m2 = 0.0;      ///< overlapping area, measured in the plane
};

/// What detection found: the pairs, and for each mesh the displacement of each vertex (in
/// metres, empty for a mesh that does not move) that puts the target in front.
struct CoincidentGeometry {
  std::vector<Coincidence> pairs;                      ///< sorted by (a, b, kind)
  std::vector<std::vector<glm::dvec3>> displacements;  ///< per mesh; empty: unchanged
};

/// Upper bound of offset_ray_origin's shift of one coordinate whose magnitude is at most
/// `magnitude_m` (in the tracer's re-centred coordinates): 256 float ULPs, or 1/65536 m near
/// the origin.
double ray_offset_bound_m(double magnitude_m);

/// Finds coincident triangles between meshes (never within one mesh). `origin` is the
/// re-centring the tracer uses (tolerances depend on the coordinates' magnitude there);
/// `is_target[i]`: mesh i is a surface target; `movable[i]`: mesh i is excluded (its position
/// changes from run to run). Cost: about linear in the triangle count (hierarchical grid).
CoincidentGeometry find_coincident(const Scene& scene, const glm::dvec3& origin,
                                   const std::vector<bool>& is_target,
                                   const std::vector<bool>& movable);

/// One line per pair, naming both meshes and the area, for Results::warnings.
Warnings coincidence_warnings(const Scene& scene, const std::vector<Coincidence>& pairs);

}  // namespace lightsolver::detail
