#include "embree/hit_triangles.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>
#include <new>

namespace lightsolver::detail {
namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

HitTriangle* allocate(std::size_t count) {
  const std::size_t bytes = std::max<std::size_t>(count, 1) * sizeof(HitTriangle);
  const bool huge = bytes >= kHugePage;
  // aligned_alloc needs a size that is a multiple of the alignment.
  const std::size_t align = huge ? kHugePage : alignof(HitTriangle);
  const std::size_t rounded = (bytes + align - 1) / align * align;
  void* p = std::aligned_alloc(align, rounded);
  if (p == nullptr) throw std::bad_alloc();
  // Advice only: where THP is off, the array simply stays on small pages.
  if (huge) madvise(p, rounded, MADV_HUGEPAGE);
  return static_cast<HitTriangle*>(p);
}

}  // namespace

void HitTriangles::Free::operator()(HitTriangle* p) const { std::free(p); }

HitTriangles::HitTriangles(const PreparedScene& s) {
  std::size_t total = 0;
  for (const PreparedMesh& m : s.meshes) {
    first_.push_back(total);
    total += m.normals.size();
  }
  data_.reset(allocate(total));
  HitTriangle* out = data_.get();
  for (const PreparedMesh& m : s.meshes) {
    auto vertex = [&](std::uint32_t k) {
      return vec3(m.vertices[3 * k], m.vertices[3 * k + 1], m.vertices[3 * k + 2]);
    };
    for (std::size_t t = 0; t < m.normals.size(); ++t) {
      const vec3 v0 = vertex(m.indices[3 * t]);
      *out++ = {v0, vertex(m.indices[3 * t + 1]) - v0, vertex(m.indices[3 * t + 2]) - v0,
                m.normals[t]};
    }
  }
}

}  // namespace lightsolver::detail
