#include "embree/embree_scene.hpp"

#include <stdexcept>
#include <string>

#include "lightsolver/timings.hpp"

namespace lightsolver::detail {
namespace {

void check(RTCDevice device, const char* step) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree failed at ") + step + " (error " +
                             std::to_string(static_cast<int>(e)) + ")");
  }
}

RTCGeometry triangle_geometry(RTCDevice device, const PreparedMesh& m) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m.vertices.data(), 0,
                             3 * sizeof(float), (m.vertices.size() - 1) / 3);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m.indices.data(), 0,
                             3 * sizeof(std::uint32_t), m.indices.size() / 3);
  rtcCommitGeometry(g);
  return g;
}

RTCScene new_scene(RTCDevice device, RTCBuildQuality quality) {
  RTCScene scene = rtcNewScene(device);
  // Robust mode makes traversal watertight: photons must not leak through shared edges of a
  // closed room, or flux conservation breaks.
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, quality);
  return scene;
}

RTCGeometry instance_of(RTCDevice device, RTCScene scene, const glm::mat4& transform) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(g, scene);
  rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
  rtcCommitGeometry(g);
  return g;
}

}  // namespace

// Without movable meshes every triangle sits in one scene. With them, the top level holds only
// instances — one for all static geometry, one per movable mesh — so moving a mesh rebuilds a
// BVH over a handful of boxes instead of over every static triangle.
EmbreeScene::EmbreeScene(const PreparedScene& scene)
    : instanced_(scene.meshes.size(), nullptr), instances_(scene.meshes.size(), nullptr) {
  {
    const timings::Scope phase("Embree device");
    device_ = rtcNewDevice(nullptr);
  }
  if (!device_) throw std::runtime_error("Embree: cannot create a device (unsupported CPU?)");
  bool any_movable = false;
  for (const auto& m : scene.meshes) any_movable = any_movable || m.movable;
  scene_ = new_scene(device_, any_movable ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
  RTCScene statics = scene_;
  if (any_movable) {
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_ROBUST);
    static_scene_ = new_scene(device_, RTC_BUILD_QUALITY_HIGH);
    statics = static_scene_;
  }
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const PreparedMesh& m = scene.meshes[i];
    if (m.indices.empty()) continue;  // every triangle was degenerate; nothing to hit
    RTCGeometry g = triangle_geometry(device_, m);
    if (m.movable) {
      // Its own BVH, built once; the instance's transform moves it (geometry ID 0 inside).
      instanced_[i] = new_scene(device_, RTC_BUILD_QUALITY_HIGH);
      rtcAttachGeometryByID(instanced_[i], g, 0);
      rtcCommitScene(instanced_[i]);
      instances_[i] = instance_of(device_, instanced_[i], m.transform);
      rtcAttachGeometryByID(scene_, instances_[i], static_cast<unsigned>(i));
    } else {
      rtcAttachGeometryByID(statics, g, static_cast<unsigned>(i));
    }
    rtcReleaseGeometry(g);
    check(device_, "geometry setup");
  }
  if (any_movable) {
    rtcCommitScene(static_scene_);
    static_instance_id_ = static_cast<unsigned>(scene.meshes.size());
    RTCGeometry g = instance_of(device_, static_scene_, glm::mat4(1.0f));
    rtcAttachGeometryByID(scene_, g, static_instance_id_);
    rtcReleaseGeometry(g);
  }
  const timings::Scope phase("BVH build");
  rtcCommitScene(scene_);
  check(device_, "BVH build");
}

void EmbreeScene::set_transform(std::size_t mesh, const glm::mat4& transform) {
  if (mesh >= instances_.size() || !instances_[mesh]) {
    throw std::logic_error("mesh " + std::to_string(mesh) + " is not instanced");
  }
  rtcSetGeometryTransform(instances_[mesh], 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transform[0][0]);
  rtcCommitGeometry(instances_[mesh]);
  rtcCommitScene(scene_);
  check(device_, "instance update");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (static_scene_) rtcReleaseScene(static_scene_);
  for (RTCGeometry g : instances_) {
    if (g) rtcReleaseGeometry(g);
  }
  for (RTCScene s : instanced_) {
    if (s) rtcReleaseScene(s);
  }
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace lightsolver::detail
