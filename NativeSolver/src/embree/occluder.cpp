// The opaque meshes' shadow rays (occluder.hpp).
#include "embree/occluder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lightsolver/scene.hpp"

namespace lightsolver {

Occluder::Occluder(const Scene& scene) {
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
    throw std::runtime_error("Embree failed building the shadow rays' BVH of the opaque meshes");
}

Occluder::~Occluder() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

double Occluder::start_offset(const glm::dvec3& origin) {
  const double scale = std::max({std::abs(origin.x), std::abs(origin.y), std::abs(origin.z)});
  return 1e-4 + scale * 0x1p-20;
}

bool Occluder::unobstructed(const glm::dvec3& origin, const glm::dvec3& direction,
                            double tfar) const {
  RTCRay ray{};
  ray.org_x = float(origin.x);
  ray.org_y = float(origin.y);
  ray.org_z = float(origin.z);
  ray.dir_x = float(direction.x);
  ray.dir_y = float(direction.y);
  ray.dir_z = float(direction.z);
  ray.tnear = float(start_offset(origin));
  ray.tfar = float(tfar);
  if (!(ray.tfar > ray.tnear)) return true;  // nothing left to cross
  ray.mask = 0xFFFFFFFFu;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene_, &context, &ray);
  return ray.tfar >= 0.0f;  // Embree sets tfar to -inf when something is hit
}

void Occluder::add_mesh(const Mesh& m) {
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

}  // namespace lightsolver
