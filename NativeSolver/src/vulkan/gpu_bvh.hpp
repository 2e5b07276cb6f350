#pragma once
// BVH for the compute shader: built on the CPU by Embree's rtcBuildBVH (binned SAH), then
// flattened depth-first into gpu::Node records with triangles stored in leaf order. Static
// meshes share the BVH rooted at node 0; each movable mesh gets its own BVH in its prepared
// coordinates, appended after it, which an instance places in the world.
#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "model/prepared_scene.hpp"
#include "vulkan/gpu_layout.hpp"

namespace lightsolver::detail {

struct GpuInstanceRoot {
  std::uint32_t mesh, root;  // the movable mesh and the root node of its BVH
  glm::vec3 lo, hi;          // its box in prepared coordinates
};

struct GpuGeometry {
  std::vector<gpu::Node> nodes;            // nodes[0] is the root; never empty
  std::vector<gpu::Tri> tris;              // leaf order
  std::vector<glm::vec4> normals;          // unit front normal of tris[i]
  std::vector<GpuInstanceRoot> instances;  // one per movable mesh, in mesh order
};

/// Builds the GPU geometry. Throws std::runtime_error when Embree fails.
GpuGeometry build_gpu_geometry(const PreparedScene& scene);

}  // namespace lightsolver::detail
