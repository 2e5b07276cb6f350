// EN 17037 sunlight exposure's shadow rays (lightsolver/sunlight.hpp): does anything opaque of
// the scene lie between a window's reference point and the sun? One Embree occlusion ray per
// point and step, through every mesh but glass (the standard's reference point is behind the
// glazing, so the pane itself never hides the sun; its transmittance is no part of the hours).
#include "embree/occluder.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver {

SunlightExposureResult sunlight_exposure(const Scene& scene) {
  if (!scene.sunlight_exposure) {
    throw InputError(scene.source_file, "sunlight_exposure",
                     "the scene has no sunlight_exposure object (docs/scene-format.md)");
  }
  validate_sunlight_exposure(*scene.sunlight_exposure, scene.source_file);
  const Occluder occluder(scene);
  return sunlight_exposure(*scene.sunlight_exposure, [&](const glm::dvec3& o, const glm::dvec3& d) {
    return occluder.unobstructed(o, d);
  });
}

}  // namespace lightsolver
