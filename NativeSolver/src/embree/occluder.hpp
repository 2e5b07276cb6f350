#pragma once
// Shadow rays through a scene's opaque meshes (Embree occlusion rays): what EN 17037's sunlight
// exposure (sunlight_rays.cpp) and the direct sun at points (direct_sun.cpp) ask. Every mesh but
// those of a `glass` material blocks: where these tests are used the glazing is accounted apart
// (the exposure counts possible sunlight; the direct sun takes its opening's τ(θ)).
#include <embree3/rtcore.h>

#include <glm/vec3.hpp>
#include <limits>

namespace lightsolver {

struct Scene;
struct Mesh;

// The scene's opaque meshes in one BVH. Built here, not shared with the photon tracer's: these
// tests are asked alone (`lightsolver sunlight`, an annual run's direct sun) as often as with a
// run, and glass is left out. Queries are const and thread-safe (Embree's rtcOccluded1).
class Occluder {
 public:
  explicit Occluder(const Scene& scene);
  ~Occluder();
  Occluder(const Occluder&) = delete;
  Occluder& operator=(const Occluder&) = delete;

  /// Is the way from `origin` along `direction` (unit) free of opaque meshes up to distance
  /// `tfar`? It starts past the float rounding of the origin (2⁻²⁰ of its largest coordinate)
  /// and past a surface the origin was placed on: 0.1 mm (start_offset()).
  bool unobstructed(const glm::dvec3& origin, const glm::dvec3& direction,
                    double tfar = std::numeric_limits<double>::infinity()) const;

  /// The distance a ray from `origin` skips: 10⁻⁴ m + 2⁻²⁰ of its largest coordinate.
  static double start_offset(const glm::dvec3& origin);

 private:
  void add_mesh(const Mesh& m);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace lightsolver
