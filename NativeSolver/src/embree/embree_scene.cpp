#include "embree/embree_scene.hpp"

#include <stdexcept>
#include <string>

namespace lightsolver::detail {
namespace {

void check(RTCDevice device, const char* step) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree failed at ") + step + " (error " +
                             std::to_string(static_cast<int>(e)) + ")");
  }
}

}  // namespace

EmbreeScene::EmbreeScene(const PreparedScene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device (unsupported CPU?)");
  scene_ = rtcNewScene(device_);
  // Robust mode makes traversal watertight: photons must not leak through shared edges of a
  // closed room, or flux conservation breaks.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const PreparedMesh& m = scene.meshes[i];
    if (m.indices.empty()) continue;  // every triangle was degenerate; nothing to hit
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.vertices.data(),
                               0, 3 * sizeof(float), (m.vertices.size() - 1) / 3);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                               3 * sizeof(std::uint32_t), m.indices.size() / 3);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, static_cast<unsigned>(i));
    rtcReleaseGeometry(g);
    check(device_, "geometry setup");
  }
  rtcCommitScene(scene_);
  check(device_, "BVH build");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace lightsolver::detail
