#pragma once
// The per-triangle data a hit needs, packed for the tracer's one memory access per hit.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

// What a hit needs of its triangle, in one cache line: on large models the BVH leaves hold
// their own triangle copies, so the scene's vertex, index and normal arrays are cold and four
// scattered reads per hit would cost more than the intersection. e1, e2 are exactly the float
// differences the interpolation used to compute, so results are unchanged to the bit.
struct alignas(64) HitTriangle {
  vec3 v0, e1, e2, n;
};

// All meshes' hit records in one array. A hit on a large model touches a random record: with
// 4 KiB pages that is a TLB miss (and a page walk) on top of the cache miss, which the
// tracer's prefetch cannot hide. Arrays of 2 MiB and more are therefore placed on transparent
// huge pages where the kernel allows it (measured: +7 % photons/s on 1M triangles).
class HitTriangles {
 public:
  explicit HitTriangles(const PreparedScene& s);

  const HitTriangle& at(unsigned mesh, unsigned primitive) const {
    return data_[first_[mesh] + primitive];
  }

 private:
  struct Free {
    void operator()(HitTriangle* p) const;
  };
  std::unique_ptr<HitTriangle[], Free> data_;
  std::vector<std::size_t> first_;  // per mesh: index of its first triangle
};

}  // namespace lightsolver::detail
