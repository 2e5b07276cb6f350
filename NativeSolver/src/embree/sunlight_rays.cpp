// EN 17037 sunlight exposure's shadow rays (lightsolver/sunlight.hpp): does anything opaque of
// the scene lie between a window's reference point and the sun? One Embree occlusion ray per
// point and step, through every mesh but glass (the standard's reference point is behind the
// glazing, so the pane itself never hides the sun; its transmittance is no part of the hours).
#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "lightsolver/scene.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver {
namespace {

// The scene's opaque meshes in one BVH. Built here, not shared with the photon tracer's: the
// exposure is asked alone (`lightsolver sunlight`) as often as with a run, and glass is left out.
class Occluder {
 public:
  explicit Occluder(const Scene& scene) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: cannot create a device (unsupported CPU?)");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);  // watertight: no leak through shared edges
    for (const Mesh& m : scene.meshes) {
      if (m.triangles.empty()) continue;
      const int mat = m.material;
      if (mat >= 0 && std::size_t(mat) < scene.materials.size() &&
          scene.materials[mat].type == Material::Type::Glass)
        continue;
      add_mesh(m);
    }
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
      throw std::runtime_error("Embree failed building the sunlight exposure's shadow BVH");
  }
  ~Occluder() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  Occluder(const Occluder&) = delete;
  Occluder& operator=(const Occluder&) = delete;

  bool unobstructed(const glm::dvec3& origin, const glm::dvec3& toward_sun) const {
    RTCRay ray{};
    ray.org_x = float(origin.x);
    ray.org_y = float(origin.y);
    ray.org_z = float(origin.z);
    ray.dir_x = float(toward_sun.x);
    ray.dir_y = float(toward_sun.y);
    ray.dir_z = float(toward_sun.z);
    // Past the float rounding of the point itself (2^-20 of its largest coordinate), and past a
    // surface the point was placed on: 0.1 mm.
    const double scale = std::max({std::abs(origin.x), std::abs(origin.y), std::abs(origin.z)});
    ray.tnear = float(1e-4 + scale * 0x1p-20);
    ray.tfar = std::numeric_limits<float>::infinity();
    ray.mask = 0xFFFFFFFFu;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(scene_, &context, &ray);
    return ray.tfar >= 0.0f;  // Embree sets tfar to -inf when something is hit
  }

 private:
  void add_mesh(const Mesh& m) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()));
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
      for (int c = 0; c < 3; ++c) v[3 * i + c] = float(m.vertices[i][c]);
    }
    auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.triangles.size()));
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
      for (int c = 0; c < 3; ++c) t[3 * i + c] = m.triangles[i][c];
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace

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
