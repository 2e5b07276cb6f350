#pragma once
/// \file direct_sun.hpp
/// Direct sunlight at points, hour by hour (docs/daylight.md, "Direct sun at points (for
/// ASE)"): the sun's beam alone, no interreflection, as IES LM-83's ASE_1000,250h counts it.
/// Deterministic: one shadow ray per point and sunlit hour (two through an opening), no photons.

#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "lightsolver/scene.hpp"

namespace lightsolver {

struct SkyMatrix;  // sky_patches.hpp

/// A daylight opening the sun's beam comes through: a parallelogram (the scene's `sun`'s own
/// opening, or a sky's portal) with its glazing.
struct SunOpening {
  glm::dvec3 corner{0.0}, edge1{0.0}, edge2{0.0};
  std::optional<GlazingDefinition> glazing;  ///< none: an open hole (τ = 1)
  /// true: the sun's own opening, which passes the beam whichever way it crosses it; false: a
  /// portal, which passes only light travelling along edge1 × edge2 (into the room).
  bool two_sided = false;
};

/// The openings the scene's direct sun comes through, from a validated scene: the first `sun`
/// luminaire's own opening (two-sided) or its portals; without a sun, the first `sky` with
/// portals; else none (an open site: every direction to the sky is a way in).
std::vector<SunOpening> sun_openings(const Scene& scene);

/// Direct sunlight (lx) at each point for each hour: hours × points, hour-major, float32.
///
/// At hour h and point p, with ŝ = sun_direction[h] (toward the sun) and E_n =
/// sun_direct_normal_lx[h]: E_n · max(0, n̂_p·ŝ) · τ when the ray from the point toward the sun
/// (the disc's centre) (a) with `openings` given, crosses one of them that passes it (the
/// nearest such; τ = its glazing's τ(θ) at the ray's incidence × frame × maintenance, as the
/// sun's flux takes it; 1 for an open hole), nothing opaque lies between the point and that
/// crossing and nothing opaque beyond it; (b) with no openings, meets nothing opaque. Glass
/// meshes never block (an opening's glazing stands for its pane). 0 where E_n is 0 or the sun
/// is not above the horizon (ŝ.z ≤ 0). Rows run in parallel (TBB); the result does not depend
/// on the thread count.
///
/// `sun_direction` holds hours × 3 floats and `sun_direct_normal_lx` hours values, as SkyMatrix
/// holds them; a direction may be (0, 0, 0) where E_n is 0. `normals` are unit (to 10⁻⁶).
/// Throws InputError (file "direct_sun_lx") naming the field: `normals` or `sun_direction`
/// sized unlike `points` / 3 × hours, `points[i]` not finite, `normals[i]` zero, not finite or
/// not unit, `sun_direct_normal_lx[h]` negative or not finite, `sun_direction[h]` not finite or
/// (where E_n > 0) not unit to 10⁻⁴, `openings[k]` not finite or of zero area, and
/// `openings[k].glazing.<key>` out of range (docs/daylight.md, "Glazing").
std::vector<float> direct_sun_lx(const Scene& scene, const std::vector<SunOpening>& openings,
                                 const std::vector<glm::dvec3>& points,
                                 const std::vector<glm::dvec3>& normals,
                                 const std::vector<float>& sun_direction,
                                 const std::vector<float>& sun_direct_normal_lx);

/// The same for a year of skies: `sky.sun_direction` and `sky.sun_direct_normal_lx`.
std::vector<float> direct_sun_lx(const Scene& scene, const std::vector<SunOpening>& openings,
                                 const std::vector<glm::dvec3>& points,
                                 const std::vector<glm::dvec3>& normals, const SkyMatrix& sky);

}  // namespace lightsolver
