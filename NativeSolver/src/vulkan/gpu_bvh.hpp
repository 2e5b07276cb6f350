#pragma once
// BVH for the compute shader: built on the CPU by Embree's rtcBuildBVH (binned SAH), then
// flattened depth-first into gpu::Node records with triangles stored in leaf order.
#include <glm/vec4.hpp>
#include <vector>

#include "core/prepared_scene.hpp"
#include "vulkan/gpu_layout.hpp"

namespace lightsolver::detail {

struct GpuGeometry {
  std::vector<gpu::Node> nodes;    // nodes[0] is the root; never empty
  std::vector<gpu::Tri> tris;      // leaf order
  std::vector<glm::vec4> normals;  // unit front normal of tris[i]
};

/// Builds the GPU geometry. Throws std::runtime_error when Embree fails.
GpuGeometry build_gpu_geometry(const PreparedScene& scene);

}  // namespace lightsolver::detail
