#pragma once
// RAII ownership of an Embree device and scene built from a PreparedScene, in the plain call
// order of Embree's minimal tutorial: device -> scene -> geometry -> commit -> attach -> commit.
#include <embree3/rtcore.h>

#include <vector>

#include "core/prepared_scene.hpp"

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

  /// Moves an instanced (movable) mesh: updates its instance and refits the top level only.
  void set_transform(std::size_t mesh, const glm::mat4& transform);

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> instanced_;      // per mesh: its own scene when movable, else null
  std::vector<RTCGeometry> instances_;   // per mesh: the instance geometry when movable
};

}  // namespace lightsolver::detail
