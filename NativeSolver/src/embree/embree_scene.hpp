#pragma once
// RAII ownership of an Embree device and scene built from a PreparedScene, in the plain call
// order of Embree's minimal tutorial: device -> scene -> geometry -> commit -> attach -> commit.
#include <embree3/rtcore.h>
#include <glm/mat4x4.hpp>

#include <vector>

#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

class EmbreeScene {
 public:
  /// Geometry IDs equal mesh indices. The PreparedScene must outlive this object (its vertex
  /// and index arrays are shared with Embree, not copied).
  explicit EmbreeScene(const PreparedScene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }

  /// Moves an instanced (movable) mesh: updates its instance and rebuilds the top level only.
  void set_transform(std::size_t mesh, const glm::mat4& transform);

  /// Mesh index of a hit: its geometry ID, or its instance ID for a movable mesh. Static
  /// geometry sits behind one identity instance when the scene has movable meshes.
  unsigned mesh_of(const RTCHit& hit, bool& moved) const {
    moved = hit.instID[0] != RTC_INVALID_GEOMETRY_ID && hit.instID[0] != static_instance_id_;
    return moved ? hit.instID[0] : hit.geomID;
  }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCScene static_scene_ = nullptr;      // static meshes, when some meshes are movable
  unsigned static_instance_id_ = RTC_INVALID_GEOMETRY_ID;
  std::vector<RTCScene> instanced_;      // per mesh: its own scene when movable, else null
  std::vector<RTCGeometry> instances_;   // per mesh: the instance geometry when movable
};

}  // namespace lightsolver::detail
