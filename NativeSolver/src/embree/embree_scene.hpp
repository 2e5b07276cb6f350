#pragma once
// RAII ownership of an Embree device and scene built from a PreparedScene, in the plain call
// order of Embree's minimal tutorial: device -> scene -> geometry -> commit -> attach -> commit.
#include <embree3/rtcore.h>

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

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace lightsolver::detail
